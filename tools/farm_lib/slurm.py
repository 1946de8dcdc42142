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
    if check and proc.returncode != 0:
        raise SlurmError(f"{' '.join(cmd)}: {(proc.stderr or proc.stdout).strip()}")
    return proc


def sbatch(args):
    """Submits; returns the job id (sbatch --parsable prints 'id' or 'id;cluster')."""
    out = run(["sbatch", "--parsable", *args]).stdout.strip()
    return out.split(";")[0]


def queued(job_ids):
    """Lines 'id state reason' of the given jobs (array tasks expanded) still in the queue."""
    proc = run(["squeue", "-h", "-r", "-j", ",".join(job_ids), "-o", "%i %T %r"], check=False)
    if proc.returncode != 0:
        # squeue errors on ids the controller no longer knows: nothing of them is queued.
        return []
    return [line for line in proc.stdout.splitlines() if line.strip()]


def job_records(job_id):
    """{field: value} of every record scontrol still has for a job (one per array task)."""
    proc = run(["scontrol", "-o", "show", "job", str(job_id)], check=False)
    records = []
    for line in proc.stdout.splitlines():
        fields = {}
        for item in line.split():
            key, _, value = item.partition("=")
            fields[key] = value
        if fields:
            records.append(fields)
    return records


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


def requeue(job_id):
    return run(["scontrol", "requeue", str(job_id)], check=False)
