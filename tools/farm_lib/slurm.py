"""Thin wrappers over Slurm's own commands (sbatch, squeue, scontrol, scancel, sacct)."""

import os
import shutil
import subprocess

from . import cluster


class SlurmError(RuntimeError):
    pass


def env():
    """The environment for Slurm commands: SLURM_CONF as given, else the local cluster's."""
    result = dict(os.environ)
    if "SLURM_CONF" not in result:
        root = cluster.current()
        if root is not None:
            result["SLURM_CONF"] = str(root / "slurm.conf")
    return result


def available():
    """None when sbatch & co. are installed and a controller answers, else why not."""
    missing = [n for n in ("sbatch", "squeue", "scancel", "scontrol") if not shutil.which(n)]
    if missing:
        return (f"Slurm commands not found: {', '.join(missing)} (install slurm-wlm, or start a "
                f"test cluster with 'tools/farm.py local-cluster start')")
    proc = run(["scontrol", "ping"], check=False)
    if proc.returncode != 0 or "UP" not in proc.stdout:
        return (f"no Slurm controller answers ({(proc.stdout + proc.stderr).strip()}); "
                f"for a test cluster on this machine: tools/farm.py local-cluster start")
    return None


def run(cmd, check=True, timeout=60):
    try:
        proc = subprocess.run(cmd, env=env(), capture_output=True, text=True, timeout=timeout,
                              stdin=subprocess.DEVNULL)
    except FileNotFoundError:
        raise SlurmError(f"{cmd[0]} not found (install slurm-wlm)") from None
    except subprocess.TimeoutExpired as exc:
        said = exc.stderr or b""
        said = (said.decode(errors="replace") if isinstance(said, bytes) else said).strip()
        said = f"; it said: {said.splitlines()[-1]}" if said else ""
        raise SlurmError(f"{cmd[0]} did not answer within {timeout:g} s (the Slurm controller "
                         f"may be overloaded or down{said})") from None
    if check and proc.returncode != 0:
        raise SlurmError(f"{' '.join(cmd)}: {(proc.stderr or proc.stdout).strip()}")
    return proc


def sbatch(args, timeout=60):
    """Submits; returns the job id (sbatch --parsable prints 'id' or 'id;cluster')."""
    out = run(["sbatch", "--parsable", *args], timeout=timeout).stdout.strip()
    job_id = out.split(";")[0]
    if not job_id.isdigit():
        raise SlurmError(f"sbatch printed no job id: {out!r}")
    return job_id


def queued(job_ids):
    """Lines 'id state reason' of the given jobs (array tasks expanded) still in the queue."""
    proc = run(["squeue", "-h", "-r", "-j", ",".join(job_ids), "-o", "%i %T %r"], check=False)
    if proc.returncode != 0:
        # squeue errors on ids the controller no longer knows: nothing of them is queued.
        return []
    return [line for line in proc.stdout.splitlines() if line.strip()]


# squeue's fields for job_records; WorkDir last, since only it may hold the separator.
_FIELDS = ("JobID", "ArrayJobID", "ArrayTaskID", "State", "Reason", "RestartCnt", "WorkDir")


def job_records(job_ids):
    """{field: value} (_FIELDS) of every job or array task the controller still remembers among
    `job_ids`, each array task on its own. squeue prints WorkDir whole (scontrol's 'Key=Value'
    lines cannot be split where a folder name holds a space)."""
    fmt = ",".join(f"{name}:|" for name in _FIELDS[:-1]) + f",{_FIELDS[-1]}:"
    proc = run(["squeue", "-h", "-r", "-t", "all", "-j", ",".join(map(str, job_ids)),
                "-O", fmt], check=False)
    if proc.returncode != 0:
        # squeue errors on ids the controller does not know.
        return []
    records = []
    for line in proc.stdout.splitlines():
        values = line.split("|", len(_FIELDS) - 1)
        if len(values) == len(_FIELDS):
            records.append(dict(zip(_FIELDS, (v.strip() for v in values))))
    return records


def jobs_in(work_dir):
    """Ids of the jobs the controller remembers whose working folder is `work_dir`."""
    proc = run(["squeue", "-h", "-t", "all", "-O", "JobID:|,WorkDir:"], check=False)
    ids = set()
    for line in proc.stdout.splitlines():
        job_id, _, folder = line.partition("|")
        if folder.strip() == str(work_dir):
            ids.add(job_id.strip())
    return sorted(ids)


def limits():
    """The cluster's MaxArraySize and MaxJobCount ({name: int}; a name is missing where
    `scontrol show config` does not say)."""
    proc = run(["scontrol", "show", "config"], check=False)
    found = {}
    for line in proc.stdout.splitlines():
        key, _, value = line.partition("=")
        key, value = key.strip(), value.strip()
        if key in ("MaxArraySize", "MaxJobCount") and value.isdigit():
            found[key] = int(value)
    return found


def job_count():
    """How many jobs the controller holds (each array task counts, as in its MaxJobCount; so do
    finished jobs until MinJobAge), or None when squeue does not say."""
    proc = run(["squeue", "-h", "-r", "-t", "all", "-o", "%i"], check=False)
    if proc.returncode != 0:
        return None
    return sum(1 for line in proc.stdout.splitlines() if line.strip())


def accounting(job_ids):
    """sacct's 'JobID|State|ExitCode' lines, or None where accounting is disabled."""
    if not shutil.which("sacct"):
        return None
    proc = run(["sacct", "-n", "-P", "-X", "-j", ",".join(job_ids), "-o",
                "JobID,State,ExitCode"], check=False)
    if proc.returncode != 0:
        return None
    return [line for line in proc.stdout.splitlines() if line.strip()]


def cancel(job_ids):
    run(["scancel", *job_ids])


def requeue(job):
    """Re-queues `job`: a job id, or 'ARRAYID_TASK' for one task of an array (the array's own
    id would re-queue every task, finished ones too)."""
    return run(["scontrol", "requeue", str(job)], check=False)
