"""`python -m rtw animate TRACE.parquet OUT.gif`: watch a gait (docs/animation.md).
`python -m rtw report DIR --out FILE.html`: a scan (docs/report.md), or a design
search or atlas (docs/design.md), as one HTML page.

Make the trace with `rtw-scan simulate … --set trace_dt=0.01 --trace TRACE.parquet`
(or rtw.trace); the design (L, α, φ, strings) is read from the file's metadata.
"""

from __future__ import annotations

import argparse
import sys


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m rtw", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="command", required=True)
    an = sub.add_parser("animate", help="a trace as an animated .gif or .mp4",
                        description="Animate a trace file: rods, strings, slope, contact modes, time and "
                                    "contact state. Frame k shows simulated time START + k·SPEED/FPS, "
                                    "k = 0 … floor(DURATION·FPS/SPEED).")
    an.add_argument("trace", help="trace Parquet file (rtw-scan simulate --trace)")
    an.add_argument("out", help="output file, .gif (Pillow) or .mp4 (needs ffmpeg)")
    an.add_argument("--fps", default=25.0, help="frames per second, in [1, 100] (default 25)")
    an.add_argument("--speed", default=1.0, help="simulated seconds per real second, in [0.01, 100] (default 1)")
    an.add_argument("--start", default=None, help="first simulated time shown [s] (default: the trace's start)")
    an.add_argument("--duration", default=None, help="simulated seconds shown (default: to the trace's end)")
    an.add_argument("--width", default=480, help="width in pixels, in [160, 1920] (default 480)")
    rp = sub.add_parser("report", help="a scan, or a design search, as one self-contained HTML page",
                        description="Write one HTML file that opens offline: the scan's header and summary, "
                                    "parallel coordinates with brushing, parallel categories, the failure "
                                    "clusters, sensitivity indices when present, and the gaits of "
                                    "representative samples, animated (docs/report.md). A design search's "
                                    "folder (rtw-scan design --out DIR) or an atlas (results/design) gives "
                                    "the design page: the search, its designs' checked slope intervals, "
                                    "their profiles and animations (docs/design.md).")
    rp.add_argument("dir", help="scan directory (samples.parquet or part-*.parquet), a scan Parquet file, "
                                "or a design search's folder or atlas")
    rp.add_argument("--out", default=None, help="the HTML file (default DIR/report.html)")
    rp.add_argument("--outputs", default=None,
                    help="comma-separated output columns beside the inputs (default speed,f_w,mu_required)")
    rp.add_argument("--per-outcome", type=int, default=2,
                    help="samples per outcome whose gait is computed, in [0, 10] (default 2)")
    rp.add_argument("--sample", type=int, action="append", default=[],
                    help="also compute this sample_id's gait (repeatable)")
    rp.add_argument("--force", action="store_true", help="write over a file that is not an rtw report")
    rp.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    a = ap.parse_args(argv)
    if a.command == "report":
        return _report(a)

    # Imported here so that `--help` answers without matplotlib.
    from .animation import animate, saver

    flags = {"fps": "--fps", "speed": "--speed", "start": "--start", "duration": "--duration", "width": "--width"}
    try:
        saver(a.out, "OUT")  # before the frames are drawn
        anim = animate(a.trace, fps=a.fps, speed=a.speed, start=a.start, duration=a.duration,
                       width=a.width, names=flags)
        anim.save(a.out)
    except (ValueError, FileNotFoundError, RuntimeError) as e:
        print(f"python -m rtw animate: error: {e}", file=sys.stderr)
        return 2
    print(f"rtw: {anim.frame_count} frames at {anim.fps:g} fps written to {a.out}", file=sys.stderr)
    return 0


def _report(a: argparse.Namespace) -> int:
    import time

    from .report import report

    outputs = None if a.outputs is None else [c.strip() for c in a.outputs.split(",") if c.strip()]
    t0 = time.monotonic()
    try:
        out = report(a.dir, a.out, outputs=outputs, per_outcome=a.per_outcome, samples=a.sample, force=a.force,
                     progress=not a.quiet)
    except (ValueError, FileNotFoundError, ImportError) as e:
        print(f"python -m rtw report: error: {e}", file=sys.stderr)
        return 2
    size = out.stat().st_size
    print(f"rtw: report written to {out} ({size / 1e6:.2f} MB, {time.monotonic() - t0:.1f} s)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
