#!/usr/bin/python3
"""Renders Photon frames on a Slurm cluster. Photon is deterministic (same seed, same pixels for
any thread count and tile order), so a frame split into bands on several nodes stitches into
exactly the image one machine makes.

    tools/farm.py submit FILE.blend --out DIR [--frames A-B] [--split N [--no-shared-prepare]]
                         [--partition P] [--wait] [--retries N] [--sbatch-timeout S]
    tools/farm.py status JOB        # exits 1 once finished with frames missing
    tools/farm.py cancel JOB        # JOB: a job id submit printed
    tools/farm.py local-cluster start|stop

submit queues one job-array task per frame (Blender's -a, with the file's output format), or
with --split N, N tasks per frame each rendering one horizontal band through the render border,
and a stitch job (afterok) assembling every channel of each frame. With --split and the
PHOTON_MAP integrator, a prepare task per frame first traces the photon maps and builds the
caches once and saves them; the frame's bands (afterok) load them instead of each preparing
again (--no-shared-prepare turns this off). Failed tasks re-queue themselves (--retries); Slurm
re-queues pre-empted ones (--requeue). The tasks run Blender with BLENDER_USER_SCRIPTS set to
--addon-dir (default: build/stage of this checkout). Every file is written under a temporary
name, read back and renamed; a write that fails (a full disk) fails its task. A submission
larger than the cluster takes (MaxArraySize, MaxJobCount) is refused before anything is queued;
one that cannot be queued whole (sbatch fails or exceeds --sbatch-timeout) is withdrawn.

Exit status: 0 done (or queued, without --wait); 1 frames failed (submit --wait, or status of a
finished submission); 2 refused (bad input, not a submission's job id, Slurm errors); 130
interrupted.
"""

import argparse
import os
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from farm_lib import blend_info, cluster, files, jobs, slurm, tasks  # noqa: E402

REPO = Path(__file__).resolve().parents[1]


def _fail(message):
    print(f"farm: error: {message}", file=sys.stderr)
    return 2


def cmd_submit(args):
    blend = Path(args.blend)
    out_dir = Path(args.out).absolute()
    addon_dir = Path(args.addon_dir)
    made = _missing_folders(out_dir)
    manifest = None
    try:
        jobs.check_arguments(blend, out_dir, args.split, addon_dir, args.blender,
                            args.retries)
        if args.sbatch_timeout <= 0:
            raise jobs.SubmitError(f"--sbatch-timeout must be more than 0, not "
                                   f"{args.sbatch_timeout}")
        first, last = jobs.parse_frames(args.frames) if args.frames else (None, None)
        reason = slurm.available()
        if reason:
            raise jobs.SubmitError(reason)
        info = blend_info.read(args.blender, blend.resolve(), out_dir, first, last,
                               addon_dir=addon_dir)
        jobs.check_settings(info, args.split)
        shared, note = jobs.shared_prepare_plan(info, args.split, not args.no_shared_prepare)
        jobs.check_capacity(len(info["frames"]), args.split, shared)
        manifest = jobs.make_manifest(blend, out_dir, info, args.split, addon_dir, args.blender,
                                      args.retries, shared)
        prepare_id, render_ids, stitch_id = jobs.submit(manifest, args.partition,
                                                        f"photon-{blend.stem}",
                                                        args.sbatch_timeout)
    except (jobs.SubmitError, blend_info.BlendError, slurm.SlurmError, files.FileError) as exc:
        return _fail(f"{exc}{_withdraw(manifest, made)}")
    except KeyboardInterrupt:
        print(f"\nfarm: submission interrupted{_withdraw(manifest, made)}",
              file=sys.stderr)
        return 130
    frames = manifest["frames"]
    if prepare_id:
        print(f"prepare job {prepare_id}: the photon maps and caches of each frame, once, "
              f"shared by its bands")
    elif note:
        print(f"farm: note: {note}")
    bands = f" x {args.split} bands" if args.split > 1 else ""
    if len(render_ids) == 1:
        print(f"render job {render_ids[0]}: {len(frames)} frame(s) {frames[0]}..{frames[-1]}"
              f"{bands}")
    else:
        print(f"render jobs {', '.join(render_ids)}: one per frame {frames[0]}..{frames[-1]}"
              f"{bands} (after its prepare task)")
    if stitch_id:
        print(f"stitch job {stitch_id} (after the render job{'s' if len(render_ids) > 1 else ''})")
    print(f"logs: {manifest['job_dir']}/logs")
    if not args.wait:
        return 0
    try:
        missing = jobs.wait(manifest)
    except KeyboardInterrupt:
        print(f"\nfarm: stopped waiting; the jobs keep running (tools/farm.py cancel "
              f"{render_ids[0]})",
              file=sys.stderr)
        return 130
    except slurm.SlurmError as exc:
        return _fail(f"{exc}; stopped waiting, the jobs keep running (tools/farm.py status "
                     f"{render_ids[0]})")
    if missing:
        print(f"farm: error: frame(s) {missing} not rendered; see {manifest['job_dir']}/logs",
              file=sys.stderr)
        for line in jobs.errors(manifest):
            print(f"farm: error: {line}", file=sys.stderr)
        return 1
    print(f"farm: all {len(frames)} frame(s) written to {out_dir}")
    return 0


def _missing_folders(folder):
    """`folder` and those of its parents that do not exist yet, deepest first."""
    missing = []
    while not os.path.lexists(folder):
        missing.append(folder)
        folder = folder.parent
    return missing


def _withdraw(manifest, made):
    """Undoes a failed submission (jobs.withdraw) and removes the folders it made (`made`,
    deepest first) that are empty. Returns a line saying what was undone, or ""."""
    left = jobs.withdraw(manifest) if manifest else ""
    for folder in made:
        try:
            folder.rmdir()
        except OSError:
            break
    if left:
        return f"\nfarm: {left}"
    if manifest:
        return ("\nfarm: the submission was withdrawn: the jobs it had queued are cancelled and "
                "its job folder is removed; nothing is left to resume")
    return ""


# A Slurm job id as submit prints it: digits, no leading zero (`scontrol show job 0` lists
# every job, and an array task 'N_M' or a list is not a submission).
_JOB_ID = re.compile(r"[1-9][0-9]{0,15}")


def _submission(text):
    """(manifest, Slurm records) of the submission a job id names. Raises jobs.SubmitError with
    a clear message for anything but a job id of a farm submission Slurm still knows."""
    if not _JOB_ID.fullmatch(text):
        raise jobs.SubmitError(f"{text!r} is not a job id: give the number submit printed "
                               f"('render job N')")
    records = slurm.job_records([text])
    if not records:
        raise jobs.SubmitError(f"Slurm knows no job {text} (a finished job is forgotten after "
                               f"the cluster's MinJobAge)")
    work_dir = records[0]["WorkDir"]
    owner = {r["ArrayJobID"] if r["ArrayTaskID"] not in ("", "N/A") else r["JobID"]
             for r in records}
    try:
        manifest = jobs.load_manifest(Path(work_dir) / "manifest.json")
    except files.FileError as exc:
        raise jobs.SubmitError(f"job {text} is not a farm submission ({exc}); use squeue / "
                               f"scancel for it") from None
    if not owner & set(jobs.job_ids(manifest)):
        raise jobs.SubmitError(f"job {text} is not one of the jobs of the submission in "
                               f"{work_dir}; use squeue / scancel for it")
    return manifest, records


def _task_name(record):
    if record["ArrayTaskID"] not in ("", "N/A"):
        return f"{record['ArrayJobID']}_{record['ArrayTaskID']}"
    return record["JobID"]


def cmd_status(args):
    reason = slurm.available()
    if reason:
        return _fail(reason)
    try:
        manifest, _ = _submission(args.job)
        ids = jobs.job_ids(manifest)
        records = slurm.job_records(ids)
        accounting = slurm.accounting(ids)
        queued = slurm.queued(ids)
    except (jobs.SubmitError, slurm.SlurmError) as exc:
        return _fail(exc)
    for record in sorted(records, key=lambda r: [int(x) for x in re.findall(r"\d+",
                                                                          _task_name(r))]):
        restarts = record["RestartCnt"]
        extra = f" (restarts {restarts})" if restarts not in ("", "0") else ""
        extra += f" [{record['Reason']}]" if record["Reason"] not in ("", "None") else ""
        print(f"{_task_name(record):>12}  {record['State']}{extra}")
    for line in accounting or []:
        print(f"sacct: {line}")
    missing = jobs.missing_frames(manifest)
    done = len(manifest["frames"]) - len(missing)
    print(f"frames done: {done}/{len(manifest['frames'])}; logs: {manifest['job_dir']}/logs")
    for line in jobs.errors(manifest):
        print(f"error: {line}")
    # Finished with frames missing: a failure, for scripts as for `submit --wait`.
    return 1 if missing and not queued else 0


def cmd_cancel(args):
    reason = slurm.available()
    if reason:
        return _fail(reason)
    try:
        manifest, _ = _submission(args.job)
        ids = jobs.job_ids(manifest)
        slurm.cancel(ids)
    except (jobs.SubmitError, slurm.SlurmError) as exc:
        return _fail(exc)
    print(f"cancelled job(s) {', '.join(ids)}")
    return 0


def cmd_local_cluster(args):
    try:
        if args.action == "start":
            root = cluster.start(args.dir)
            print(f"local Slurm cluster running in {root}")
            print(f"export SLURM_CONF={root}/slurm.conf   # farm.py finds it by itself")
        else:
            if not cluster.stop():
                print("no local cluster was running")
            else:
                print("local Slurm cluster stopped and removed")
    except cluster.ClusterError as exc:
        return _fail(exc)
    return 0


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("submit", help="queue a .blend's frames")
    p.add_argument("blend")
    p.add_argument("--out", required=True, help="output folder (file names from the .blend)")
    p.add_argument("--frames", help="A-B or A (default: the file's frame range)")
    p.add_argument("--split", type=int, default=1, help="horizontal bands per frame (1)")
    p.add_argument("--no-shared-prepare", action="store_true",
                   help="with --split: every band traces its own photon maps and caches "
                        "instead of loading the frame's shared preparation")
    p.add_argument("--partition", help="Slurm partition")
    p.add_argument("--wait", action="store_true", help="wait; exit 1 if any frame failed")
    p.add_argument("--retries", type=int, default=2,
                   help="times a failed task re-queues itself (2)")
    p.add_argument("--blender", default="blender", help="Blender executable on the nodes")
    p.add_argument("--addon-dir", default=str(REPO / "build" / "stage"),
                   help="folder holding addons/photon (BLENDER_USER_SCRIPTS)")
    p.add_argument("--sbatch-timeout", type=float, default=60.0,
                   help="seconds one sbatch may take before the submission is withdrawn (60)")
    p.set_defaults(func=cmd_submit)
    for name, func in (("status", cmd_status), ("cancel", cmd_cancel)):
        p = sub.add_parser(name, help=f"{name} a submission (its render job id)")
        p.add_argument("job")
        p.set_defaults(func=func)
    p = sub.add_parser("local-cluster", help="a single-node Slurm cluster on this machine")
    p.add_argument("action", choices=["start", "stop"])
    p.add_argument("--dir", help="cluster folder (default: a new temporary folder)")
    p.set_defaults(func=cmd_local_cluster)
    # Run by Slurm, not by people.
    for name in ("_prepare", "_task", "_stitch"):
        p = sub.add_parser(name)
        p.add_argument("manifest")
        if name == "_task":
            p.add_argument("--frame-index", type=int)
    args = parser.parse_args(argv)
    if args.command in ("_prepare", "_task", "_stitch"):
        return _run_task(args)
    return args.func(args)


def _run_task(args):
    try:
        if args.command == "_prepare":
            return tasks.run_prepare(args.manifest)
        if args.command == "_task":
            return tasks.run_task(args.manifest, args.frame_index)
        return tasks.run_stitch(args.manifest)
    except files.FileError as exc:
        # A manifest or task folder the task cannot use: no retry will do better.
        tasks.say(f"{jobs.ERROR}{exc}")
        return 1


if __name__ == "__main__":
    sys.exit(main())
