"""Benchmark: cold and warm wall time of a study, and of a 5 C10 x 5 gamma grid on one shell.

cold: a fresh temporary catalogue, every path set computed on dask (a local cluster of
processes unless --scheduler); warm: the same study again on that catalogue (all reused,
no cluster started).  The grid shows the scaling of DESIGN.md section 3: 25 points, one
set of FE paths.

Tables and figures: the time to write every table and figure from a results netCDF (read,
tables, figures), after each study, or alone with --products RESULTS.nc.

A study run again (--rerun): whole `shell-adhesion run` processes back to back on one
catalogue: cold (skipped with --catalogue DIR holding the study), warm into a new folder
(cube, tables and figures copied from the catalogue), warm into the same folder (all
kept); each with its time split: Python start, imports, the run less its products (plan,
catalogue, cube), the products (copied or drawn).

Run: python benchmarks/study.py [study.yaml] [--mesh coarse] [--workers N] [--scheduler ADDR]
     [--grid-only] [--products results/paper.nc] [--rerun [--catalogue DIR] [--repeat 3]]
The default study is workflow.yaml (11 shells on the default mesh: its cold run is long).
"""
import argparse
import json
import os
from pathlib import Path
import subprocess
import sys
import tempfile
import time

import yaml

HERE = Path(__file__).resolve().parent
# this script shares its name with the `study` package: import the package, not itself
sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != HERE]

REPO = HERE.parent
GRID = dict(
    name="grid_5x5", R_mm=20.0,
    base=dict(C10_MPa=0.3, t_over_R=0.15, h_over_R=1.0, gamma_J_m2=30.0),
    grid=dict(C10_MPa=[0.1, 0.2, 0.3, 0.5, 1.0], gamma_J_m2=[10.0, 20.0, 30.0, 40.0, 50.0]),
    interface="no_slip", mesh="default", delta_max_over_R=0.25)


def bench(doc: dict, tmp: Path, args):
    """(cold Outcome, warm Outcome) of one study document."""
    path = tmp / f"{doc['name']}.yaml"
    path.write_text(yaml.safe_dump(doc, sort_keys=False))
    from shell_adhesion.study.run import execute
    cat = tmp / f"catalogue-{doc['name']}"
    kw = dict(catalogue=cat, scheduler=args.scheduler, workers=args.workers,
              progress=not args.quiet)
    cold = execute(path, tmp / "results-cold", **kw)
    warm = execute(path, tmp / "results-warm", **kw)
    return cold, warm


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("study", nargs="?", default=str(REPO / "workflow.yaml"))
    p.add_argument("--mesh", default=None, help="override the mesh of both studies")
    p.add_argument("--workers", type=int, default=None, help="local cluster size")
    p.add_argument("--scheduler", default=None, help="dask scheduler address")
    p.add_argument("--grid-only", action="store_true", help="only the 5 x 5 grid")
    p.add_argument("--quiet", action="store_true", help="no progress bars")
    p.add_argument("--products", default=None, metavar="RESULTS.nc",
                   help="only time the tables and figures of an existing results file")
    p.add_argument("--rerun", action="store_true",
                   help="time whole runs: cold, warm into a new folder, warm in the same one")
    p.add_argument("--catalogue", default=None,
                   help="(--rerun) a catalogue holding the study: no cold run")
    p.add_argument("--repeat", type=int, default=3, help="(--rerun) runs of each warm kind")
    p.add_argument("--child", nargs=3, metavar=("STUDY", "OUT", "CATALOGUE"),
                   help=argparse.SUPPRESS)
    args = p.parse_args(argv)
    if args.child:
        child(*args.child)
        return
    if args.products:
        products(args.products)
        return
    if args.rerun:
        rerun(args)
        return

    docs = [] if args.grid_only else [yaml.safe_load(Path(args.study).read_text())]
    docs.append(dict(GRID))
    print(f"{'study':<12} {'mesh':<8} {'shells':>6} {'points':>6} {'cold s':>8} "
          f"{'computed':>8} {'warm s':>7} {'reused':>6} {'failed':>6} {'ok pts':>6}")
    with tempfile.TemporaryDirectory() as tmp:
        for doc in docs:
            if args.mesh:
                doc["mesh"] = args.mesh
            cold, warm = bench(doc, Path(tmp), args)
            print(f"{doc['name']:<12} {doc.get('mesh', 'default'):<8} "
                  f"{len(cold.plan.shells):6d} {len(cold.plan.points):6d} {cold.wall_s:8.1f} "
                  f"{len(cold.computed):8d} {warm.wall_s:7.2f} {len(warm.reused):6d} "
                  f"{len(cold.failed):6d} {cold.counts['ok']:6d}", flush=True)
            products(warm.output)


def products(results_nc):
    """Print the wall time of every table and figure written from `results_nc`."""
    from shell_adhesion.analysis.products import write_products
    pr = write_products(results_nc)
    s = pr.seconds
    print(f"  tables and figures of {results_nc}: {len(pr.tables)} tables, {len(pr.figures)} "
          f"figure files in {s['total']:.2f} s (read {s['read']:.2f} s, tables "
          f"{s['tables']:.2f} s, figures {s['figures']:.2f} s); skipped: {pr.skipped or 'none'}",
          flush=True)


def child(study, out, catalogue):
    """One run as `shell-adhesion run` makes it (this process's imports timed): a JSON line
    of its time split."""
    t0 = time.perf_counter()
    import shell_adhesion.cli  # noqa: F401  (what the command imports)
    from shell_adhesion.study.run import execute
    t1 = time.perf_counter()
    outcome = execute(study, out, catalogue=catalogue, progress=False)
    t2 = time.perf_counter()
    pr = outcome.products
    mode = "kept" if pr.kept else "copied" if pr.copied else "drawn"
    print(json.dumps(dict(imports_s=t1 - t0, run_s=t2 - t1,
                          products_s=pr.seconds.get("total", 0.0), products=mode,
                          computed=len(outcome.computed), exit_code=outcome.exit_code)))


def _timed_run(study, out, catalogue):
    """(process wall s, the child's split) of one run in a new Python process."""
    env = dict(os.environ, PYTHONPATH=str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    t0 = time.perf_counter()
    done = subprocess.run([sys.executable, __file__, "--child", str(study), str(out),
                           str(catalogue)], capture_output=True, text=True, env=env)
    wall = time.perf_counter() - t0
    if done.returncode != 0:
        raise SystemExit(f"run into {out} failed:\n{done.stderr[-2000:]}")
    return wall, json.loads(done.stdout.strip().splitlines()[-1])


def rerun(args):
    """Cold, warm into new folders, warm in the same folder: one row per run."""
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        study = Path(args.study).resolve()
        if args.mesh:
            doc = yaml.safe_load(study.read_text())
            doc["mesh"] = args.mesh
            study = tmp / study.name
            study.write_text(yaml.safe_dump(doc, sort_keys=False))
        cat = Path(args.catalogue) if args.catalogue else tmp / "catalogue"
        runs = [] if args.catalogue else [("cold", tmp / "cold")]
        runs += [(f"warm, new folder {i + 1}", tmp / f"new{i}") for i in range(args.repeat)]
        runs += [(f"warm, same folder {i + 1}", tmp / "new0") for i in range(args.repeat)]
        print(f"study {study} on the catalogue {cat}")
        print(f"{'run':<22} {'wall s':>7} {'start s':>8} {'imports s':>9} {'run s':>6} "
              f"{'of which products s':>19}  products")
        for name, out in runs:
            wall, t = _timed_run(study, out, cat)
            start = wall - t["imports_s"] - t["run_s"]
            print(f"{name:<22} {wall:7.2f} {start:8.2f} {t['imports_s']:9.2f} {t['run_s']:6.2f} "
                  f"{t['products_s']:19.2f}  {t['products']}"
                  + (f" ({t['computed']} sets computed)" if t["computed"] else ""), flush=True)


if __name__ == "__main__":
    main()
