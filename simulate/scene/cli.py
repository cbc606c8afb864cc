"""``chaplygin simulate SCENE [--out DIR] [--cross-check] [--force]``: plan, run, write, summarise.

``SCENE`` is a scene file or the name of a built-in scene (``generic4d``; ``--list`` shows them).
Exit status: 0 done (and the cross-check, if asked, passed); 1 the cross-check failed; 2 the scene,
``--out`` or the run cannot give a right answer (one line on stderr, nothing written); 3 a kernel
is missing from ``generated/``; 130 interrupted (Ctrl-C; SIGTERM: 143 from the ``chaplygin``
program, 130 from this function) — one line, ``--out`` keeps its
previous result, :mod:`simulate.scene.outdir`). A closed stdout (``| head -1``) does not stop the run.
"""

from __future__ import annotations

import os
import sys
import time
from pathlib import Path

import numpy as np
from chaplygin_nd.simulate.integrators.stops import RunStopped, check_finite
from chaplygin_nd.simulate.kernels import KernelMissing
from chaplygin_nd.simulate.scene import tori as tori_scene
from chaplygin_nd.simulate.scene.frequency_map import FrequencyMapScene
from chaplygin_nd.simulate.scene.outdir import OutputError, claim
from chaplygin_nd.simulate.scene.outputs import collect, without_figures, write
from chaplygin_nd.simulate.scene.planner import plan
from chaplygin_nd.simulate.scene.report import heading, summary
from chaplygin_nd.simulate.scene.run import execute
from chaplygin_nd.simulate.scene.spec import SceneError, builtin_scenes, find

from chaplygin_nd.cli import version_line
from chaplygin_nd.console import (
    OneLineParser,
    fail,
    interruptible,
    path_argument,
    positive_int,
    say,
    usable_backend,
)

__all__ = ["main"]


def _parser() -> OneLineParser:
    """The options of ``chaplygin simulate``."""
    ap = OneLineParser(prog="chaplygin simulate", description=__doc__.split("\n\n")[0].replace("``", ""),
                       epilog="built-in scenes: " + ", ".join(builtin_scenes()))
    ap.add_argument("--version", action="version", version=version_line())
    ap.add_argument("scene", nargs="?",
                    help="a scene file (TOML), e.g. scenes/generic4d.toml, or a built-in scene name")
    ap.add_argument("--out", type=path_argument, help="output folder: new, empty, or written before by this scene "
                    "(default: out/<scene name>)")
    ap.add_argument("--cross-check", action="store_true",
                    help="also run an independent model and judge the difference (exit 1 on FAIL)")
    ap.add_argument("--force", action="store_true",
                    help="run even when the predicted time or memory is past the limit")
    ap.add_argument("--no-plots", action="store_true", help="skip the PNG plots")
    ap.add_argument("--list", action="store_true", help="list the built-in scenes and exit")
    ap.add_argument("--workers", type=positive_int, default=None, metavar="N",
                    help="frequency-map scenes: worker processes (default: the CPU count)")
    ap.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="frequency-map scenes: run on this Dask scheduler ('local' starts a "
                    "local cluster of --workers processes; needs the extra 'cluster')")
    return ap


def main(argv: list[str] | None = None) -> int:
    """Entry point; returns the exit status (see the module docstring)."""
    ap = _parser()
    args = ap.parse_args(argv)
    if args.list:
        for name, title in builtin_scenes().items():
            print(f"{name:<16} {title}")
        return 0
    if args.scene is None:
        ap.error("give a scene file or a built-in scene name (--list shows them)")
    start = time.perf_counter()
    out = args.out  # a Path (path_argument refuses an empty one), or None: out/<scene name>
    folder = None
    p = None  # the plan, once made (a refusal after it names the closed forms it ruled out)
    with interruptible():
        try:
            scene = find(args.scene, force=args.force)
            if not isinstance(scene, FrequencyMapScene):  # refused, not silently ignored
                for option in ("workers", "scheduler"):
                    if getattr(args, option) is not None:
                        raise SceneError(args.scene, f"--{option}", "only a frequency-map "
                                         "scene (one with [fma]) runs in worker processes, and "
                                         "this scene has no [fma] table",
                                         f"drop --{option}, or give a frequency-map scene "
                                         "(e.g. fma4d)")
            out = out or Path("out") / scene.name
            folder = claim(out, scene.name)
            # figures or none, decided once for every scene kind (outputs.without_figures drops them)
            plots = not args.no_plots and scene.figures
            if plots:
                usable_backend()
            if isinstance(scene, FrequencyMapScene):  # a frequency map (simulate/scene/frequency_map.py)
                return _frequency_map(scene, folder, out, args, start, plots)
            # inf/nan are not warned about but checked: every field and output, naming it and the time
            with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                p = plan(scene)
                say(heading(scene, p))  # before the run; the rest of the summary after it
                traj = execute(scene, p, force=args.force)
                arrays = collect(scene, traj)
                for key, v in arrays.items():
                    check_finite(key, v, scene.t if key != "zeta" else scene.t[0])
                check = None
                if args.cross_check:
                    from chaplygin_nd.simulate.scene.crosscheck import cross_check
                    state: dict[str, np.ndarray] | None = (
                        {k: traj.data[k] for k in ("M", "gamma") if k in traj.data}
                             if tori_scene.wants(scene) else None)
                    check = cross_check(scene, p, arrays, force=args.force, state=state)
                extra, extra_lines = (tori_scene.files(scene, traj, plots) if tori_scene.wants(scene)
                                      else ({}, []))
            rest = "\n".join([summary(scene, p, traj, arrays, time.perf_counter() - start, check,
                                       out, with_heading=False), *extra_lines])
            text = heading(scene, p, report=True) + "\n" + rest  # summary.txt: the whole summary
            try:
                write(folder, arrays, text, plots=plots, extra=extra)
            except OSError as exc:
                return fail(f"writing --out {out}: {exc.strerror or exc}")
        except (SceneError, OutputError) as exc:
            return fail(str(exc))
        except RunStopped as exc:  # name the closed form the target ruled out, if one was
            missed = p.missed if p is not None else None
            return fail(str(exc) + (f" (not taken: the {'; the '.join(missed)})"
                                    if missed and "closed form" not in str(exc) else ""))
        except KernelMissing as exc:
            return fail(str(exc), 3)
        except OSError as exc:
            where = exc.filename or "a file the run needed"
            return fail(f"{where}: {exc.strerror or exc}")
        except KeyboardInterrupt:
            return fail("interrupted", 130)
        finally:
            if folder is not None:
                folder.release()
    say(rest)
    return 1 if check is not None and not check.passed else 0


def _frequency_map(scene, folder, out, args, start, plots: bool) -> int:
    """Run a frequency-map scene into ``folder`` (claimed) and print its summary; without the two
    map figures when ``plots`` is false (``--no-plots``)."""
    from chaplygin_nd.simulate.analysis import fma
    from chaplygin_nd.simulate.scene import frequency_map as fma_scene

    if args.workers is not None and args.workers < 1:
        raise SceneError("--workers", "--workers", f"{args.workers}", "give N >= 1")
    cores = os.cpu_count() or 1
    if args.workers is not None and args.workers > cores and args.scheduler in (None, "local"):
        say(f"note    --workers {args.workers} is more than the {cores} cores of this machine: "
            f"running {cores} worker processes")
        args.workers = cores
    fma.require_heyoka()
    print(f"plan    frequency map: 2 x {scene.spec.size}^2 orbits of the full field "
          f"(heyoka batch), T = {2 * scene.spec.samples * scene.spec.dt:g}; "
          f"{fma.where(args.workers, args.scheduler)}", flush=True)
    files, text = fma_scene.run(scene, workers=args.workers, scheduler=args.scheduler)
    text += f"\nwall    {time.perf_counter() - start:.1f} s in all\nwritten {out}"
    folder.write(files if plots else without_figures(files))
    print(text)
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
