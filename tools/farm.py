#!/usr/bin/python3
"""Renders Photon frames on a Slurm cluster. Photon is deterministic (same seed, same pixels for
any thread count and tile order), so a frame split into bands on several nodes stitches into
exactly the image one machine makes.

    tools/farm.py submit FILE.blend --out DIR [--frames A-B] [--split N [--no-shared-prepare]]
                         [--partition P] [--wait]
    tools/farm.py status JOB
    tools/farm.py cancel JOB
    tools/farm.py local-cluster start|stop

submit queues one job-array task per frame (Blender's -a, with the file's output format), or
with --split N, N tasks per frame each rendering one horizontal band through the render border,
and a stitch job (afterok) assembling every channel of each frame. With --split and the
PHOTON_MAP integrator, a prepare task per frame first traces the photon maps and builds the
caches once and saves them; the frame's bands (afterok) load them instead of each preparing
again (--no-shared-prepare turns this off). Failed tasks re-queue themselves (--retries); Slurm
re-queues pre-empted ones (--requeue). Slurm runs the tasks with BLENDER_USER_SCRIPTS set to
--addon-dir (default: build/stage of this checkout).
"""

import argparse
import json
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from farm_lib import blend_info, cluster, jobs, slurm, tasks  # noqa: E402

REPO = Path(__file__).resolve().parents[1]


def _fail(message):
    print(f"farm: error: {message}", file=sys.stderr)
    return 2


def cmd_submit(args):
    blend = Path(args.blend)
    out_dir = Path(args.out).absolute()
    addon_dir = Path(args.addon_dir)
    try:
        jobs.check_arguments(blend, out_dir, args.split, addon_dir, args.blender,
                            args.retries)
        first, last = jobs.parse_frames(args.frames) if args.frames else (None, None)
        reason = slurm.available()
        if reason:
            raise jobs.SubmitError(reason)
        info = blend_info.read(args.blender, blend.resolve(), out_dir, first, last,
                               addon_dir=addon_dir)
        jobs.check_settings(info, args.split)
        shared, note = jobs.shared_prepare_plan(info, args.split, not args.no_shared_prepare)
        manifest = jobs.make_manifest(blend, out_dir, info, args.split, addon_dir, args.blender,
                                      args.retries, shared)
        prepare_id, render_ids, stitch_id = jobs.submit(manifest, args.partition,
                                                        f"photon-{blend.stem}")
    except (jobs.SubmitError, blend_info.BlendError, slurm.SlurmError) as exc:
        return _fail(exc)
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
    if missing:
        print(f"farm: error: frame(s) {missing} not rendered; see {manifest['job_dir']}/logs",
              file=sys.stderr)
        return 1
    print(f"farm: all {len(frames)} frame(s) written to {out_dir}")
    return 0


def _manifest_of(job_id):
    """The submission's manifest, found through the job's working folder (--chdir)."""
    for record in slurm.job_records(job_id):
        path = Path(record.get("WorkDir", "")) / "manifest.json"
        if path.is_file():
            return json.loads(path.read_text())
    return None


def cmd_status(args):
    reason = slurm.available()
    if reason:
        return _fail(reason)
    manifest = _manifest_of(args.job)
    ids = jobs.job_ids(manifest) if manifest else [args.job]
    states = {}
    for job_id in ids:
        for record in slurm.job_records(job_id):
            task = record.get("JobId")
            if record.get("ArrayTaskId"):
                task = f"{record.get('ArrayJobId')}_{record['ArrayTaskId']}"
            states[task] = (record.get("JobState", "?"), record.get("Restarts", "0"),
                            record.get("Reason", ""))
    accounting = slurm.accounting(ids)
    if not states and not accounting:
        return _fail(f"Slurm knows no job {args.job}")
    for task, (state, restarts, reason) in sorted(states.items()):
        extra = f" (restarts {restarts})" if restarts not in ("", "0") else ""
        extra += f" [{reason}]" if reason not in ("", "None") else ""
        print(f"{task:>12}  {state}{extra}")
    for line in accounting or []:
        print(f"sacct: {line}")
    if manifest:
        missing = jobs.missing_frames(manifest)
        done = len(manifest["frames"]) - len(missing)
        print(f"frames done: {done}/{len(manifest['frames'])}; logs: {manifest['job_dir']}/logs")
    return 0


def cmd_cancel(args):
    reason = slurm.available()
    if reason:
        return _fail(reason)
    manifest = _manifest_of(args.job)
    ids = jobs.job_ids(manifest) if manifest else [args.job]
    try:
        slurm.cancel(ids)
    except slurm.SlurmError as exc:
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
    if args.command == "_prepare":
        return tasks.run_prepare(args.manifest)
    if args.command == "_task":
        return tasks.run_task(args.manifest, args.frame_index)
    if args.command == "_stitch":
        return tasks.run_stitch(args.manifest)
    return args.func(args)


if __name__ == "__main__":
    sys.exit(main())
