"""Benchmark anchor: the base shell's frictionless loading curve in CalculiX (issue 41).

CalculiX (`ccx`, 2.20 here: `apt-get install calculix-ccx`) is not a dependency: without
`ccx` on the PATH this prints one line and exits 0.

The problem is `benchmarks/loading.py coarse frictionless`'s: the hemispherical shell
R = h = 20 mm, t = 3 mm, neo-Hooke C10 = 0.3 MPa (CalculiX: *HYPERELASTIC, NEO HOOKE with
D1 = 1e-4 /MPa, bulk modulus 2/D1 = 20000 MPa = 33000 mu: nearly incompressible),
axisymmetric, NLGEOM.  As in our model (solver.contact.constraints) the rim face is pushed
down by delta with u_r = 0 there and u_r = 0 on the axis; the outer surface meets the
rigid plane z = 0 (under the apex at delta = 0) without friction.  The mesh is ours: the
coarse mesh's Q2 quads (solver.mesh, t/R 0.15, h/R 1) without their centre nodes, as
CAX8R.  The plane is a stiff elastic slab (E = 1e5 MPa, 2 mm thick, fixed below) whose top
face is the master surface of a surface-to-surface contact pair with a linear penalty
(CONTACT_K_MPA_PER_MM); no *FRICTION card, so the contact is frictionless.  Displacement
control to delta = 5 mm in increments of at most 0.25 mm.

CalculiX expands axisymmetric elements into a 2-degree wedge, so its reaction forces are
those of 1/180 of the ring; P is 180 times minus the rim's total RF_z (positive in
compression, the paper's sign).

    python benchmarks/calculix_loading.py [--threads N] [--keep DIR] [--d1 D1]

prints the increments' P(delta), the wall time of the ccx process, its dofs, and P(5 mm).
"""
import argparse
import os
import pathlib
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time

import numpy as np

R_MM, T_MM, H_MM, C10_MPA, DELTA_MM = 20.0, 3.0, 20.0, 0.3, 5.0
D1_PER_MPA = 2.0 / (5000 * 2 * C10_MPA)   # 2 / bulk modulus: FElupe's 5000 mu
CONTACT_K_MPA_PER_MM = 100.0  # penalty: overclosure about 1e-3 mm at 0.1 MPa
SLAB_MM, SLAB_WIDTH_MM, SLAB_ELEMENTS = 2.0, 22.0, 11
WEDGE_PER_RING = 180.0       # 2 degrees of 360
MAX_INCREMENT = 0.05         # of delta = 5 mm: 0.25 mm


def shell_mesh(mesh="coarse"):
    """(nodes (n, 2) in mm as (r, z), CAX8 connectivity (m, 8) 0-based, outer-face index of
    each element (0..3: CalculiX faces S1..S4) or -1, rim nodes, axis nodes) of our mesh."""
    from shell_adhesion.solver.geometry import Cap
    from shell_adhesion.solver.mesh import cap_mesh, mesh_spec

    cm = cap_mesh(Cap(T_MM / R_MM, H_MM / R_MM), mesh_spec(mesh))
    xy = cm.nodes.T * R_MM
    edofs = cm.mesh.dofs.element_dofs[:8].T.copy()   # 4 corners, midsides 1-2, 2-3, 3-4, 4-1
    c = xy[edofs[:, :4]]
    area = 0.5 * np.sum(c[:, :, 0] * np.roll(c[:, :, 1], -1, 1)
                        - np.roll(c[:, :, 0], -1, 1) * c[:, :, 1], axis=1)
    flip = area < 0                                  # CalculiX wants corners anticlockwise
    edofs[flip] = edofs[flip][:, [0, 3, 2, 1, 7, 6, 5, 4]]
    outer = set(cm.outer.tolist())
    face = np.full(len(edofs), -1)
    for e, conn in enumerate(edofs):
        for k in range(4):
            if conn[k] in outer and conn[(k + 1) % 4] in outer:
                face[e] = k
    used = np.unique(edofs)
    return xy, edofs, face, used, cm.rim, cm.axis


def deck(mesh="coarse", d1=D1_PER_MPA):
    """The CalculiX input deck (text) and the number of nodes it has."""
    xy, conn, face, used, rim, axis = shell_mesh(mesh)
    lines = ["*HEADING", "base shell pressed on a rigid plane, frictionless (shell-adhesion)",
             "*NODE, NSET=NALL"]
    lines += [f"{i + 1}, {xy[i, 0]:.12g}, {xy[i, 1]:.12g}" for i in used]
    n0 = len(xy)
    # the slab: SLAB_ELEMENTS CAX8 quads in a row, 0 <= r <= SLAB_WIDTH_MM, -SLAB_MM <= z <= 0
    nx = 2 * SLAB_ELEMENTS + 1
    rs = np.linspace(0.0, SLAB_WIDTH_MM, nx)
    zs = np.array([-SLAB_MM, -SLAB_MM / 2, 0.0])
    sid = lambda i, j: n0 + j * nx + i + 1          # noqa: E731 (node id of the slab grid)
    slab_nodes = [(sid(i, j), rs[i], zs[j]) for j in range(3) for i in range(nx)
                  if not (j == 1 and i % 2)]
    lines += [f"{n}, {r:.12g}, {z:.12g}" for n, r, z in slab_nodes]
    lines.append("*ELEMENT, TYPE=CAX8R, ELSET=SHELL")
    lines += [f"{e + 1}, " + ", ".join(str(n + 1) for n in c) for e, c in enumerate(conn)]
    lines.append("*ELEMENT, TYPE=CAX8R, ELSET=SLAB")
    m0 = len(conn)
    for k in range(SLAB_ELEMENTS):
        i = 2 * k
        c = [sid(i, 0), sid(i + 2, 0), sid(i + 2, 2), sid(i, 2),
             sid(i + 1, 0), sid(i + 2, 1), sid(i + 1, 2), sid(i, 1)]
        lines.append(f"{m0 + k + 1}, " + ", ".join(map(str, c)))
    lines += ["*NSET, NSET=RIM"] + _rows(rim + 1)
    lines += ["*NSET, NSET=AXIS"] + _rows(axis + 1)
    lines += ["*NSET, NSET=SLABBASE"] + _rows([sid(i, 0) for i in range(nx)])
    lines += ["*SURFACE, NAME=SHELLOUT, TYPE=ELEMENT"]
    lines += [f"{e + 1}, S{face[e] + 1}" for e in np.flatnonzero(face >= 0)]
    lines += ["*SURFACE, NAME=SLABTOP, TYPE=ELEMENT"]
    lines += [f"{m0 + k + 1}, S3" for k in range(SLAB_ELEMENTS)]
    lines += ["*MATERIAL, NAME=RUBBER", "*HYPERELASTIC, NEO HOOKE", f"{C10_MPA}, {d1}",
              "*MATERIAL, NAME=STIFF", "*ELASTIC", "1e5, 0.3",
              "*SOLID SECTION, ELSET=SHELL, MATERIAL=RUBBER",
              "*SOLID SECTION, ELSET=SLAB, MATERIAL=STIFF",
              "*SURFACE INTERACTION, NAME=PLANE",
              "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR", f"{CONTACT_K_MPA_PER_MM}",
              "*CONTACT PAIR, INTERACTION=PLANE, TYPE=NODE TO SURFACE", "SHELLOUT, SLABTOP",
              "*BOUNDARY", "AXIS, 1, 1", "RIM, 1, 1", "SLABBASE, 1, 2",
              "*STEP, NLGEOM, INC=1000", "*STATIC",
              f"{MAX_INCREMENT}, 1.0, 1e-6, {MAX_INCREMENT}",
              "*CONTROLS, PARAMETERS=TIME INCREMENTATION", "8, 10, 9, 200, 10, 4, 0, 200",
              "*BOUNDARY", f"RIM, 2, 2, {-DELTA_MM}",
              "*NODE PRINT, NSET=RIM, TOTALS=ONLY", "RF",
              "*END STEP"]
    return "\n".join(lines) + "\n", len(used) + len(slab_nodes)


def _rows(ids, per=8):
    ids = [int(i) for i in ids]
    return [", ".join(map(str, ids[k:k + per])) for k in range(0, len(ids), per)]


def parse_dat(text):
    """(delta_mm, P_N) arrays of the increments in a .dat file with the rim's RF totals."""
    pat = re.compile(r"total force \(fx,fy,fz\) for set RIM and time\s+(\S+)\s*\n\s*"
                     r"(\S+)\s+(\S+)\s+(\S+)")
    out = [(float(t) * DELTA_MM, -WEDGE_PER_RING * float(fz))
           for t, _, fz, _ in pat.findall(text)]
    delta, P = (np.array(v) for v in zip(*out)) if out else (np.array([]), np.array([]))
    return delta, P


def run(mesh="coarse", threads=None, keep=None, d1=D1_PER_MPA):
    """Write the deck, run ccx on it; (wall s and CPU s of the ccx process, nodes,
    delta_mm, P_N of its increments)."""
    text, nodes = deck(mesh, d1)
    work = pathlib.Path(keep) if keep else pathlib.Path(tempfile.mkdtemp(prefix="ccx-"))
    work.mkdir(parents=True, exist_ok=True)
    (work / "shell.inp").write_text(text)
    env = dict(os.environ)
    n = str(threads or os.cpu_count() or 1)
    env.update(OMP_NUM_THREADS=n, CCX_NPROC_EQUATION_SOLVER=n, CCX_NPROC_STIFFNESS=n)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    done = subprocess.run(["ccx", "-i", "shell"], cwd=work, env=env, capture_output=True,
                          text=True, timeout=3600)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    dat = (work / "shell.dat").read_text() if (work / "shell.dat").exists() else ""
    delta, P = parse_dat(dat)
    if not keep:
        shutil.rmtree(work, ignore_errors=True)
    if done.returncode != 0 or not len(delta) or abs(delta[-1] - DELTA_MM) > 1e-9:
        tail = (done.stdout + done.stderr).strip().splitlines()[-5:]
        raise RuntimeError("ccx did not reach delta = 5 mm: " + " | ".join(tail))
    return wall, cpu, nodes, delta, P


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mesh", default="coarse")
    ap.add_argument("--threads", type=int, default=None,
                    help="ccx threads (default: every core)")
    ap.add_argument("--keep", default=None, help="keep the deck and ccx's output in DIR")
    ap.add_argument("--d1", type=float, default=D1_PER_MPA)
    ap.add_argument("--curve", action="store_true", help="print every increment")
    a = ap.parse_args(argv)
    if shutil.which("ccx") is None:
        print("calculix_loading: skipped, no ccx on the PATH (apt-get install calculix-ccx)")
        return 0
    wall, cpu, nodes, delta, P = run(a.mesh, a.threads, a.keep, a.d1)
    if a.curve:
        for d, p in zip(delta, P):
            print(f"  delta {d:6.3f} mm  P {p:9.4f} N")
    print(f"CalculiX CAX8R, {a.mesh} mesh, frictionless: {2 * nodes} dofs, {len(delta)} "
          f"increments, {wall:.2f} s ({cpu:.2f} s CPU), D1 {a.d1:.3g} /MPa, "
          f"P({DELTA_MM:g} mm) = {P[-1]:.4f} N")
    return 0


if __name__ == "__main__":
    sys.exit(main())
