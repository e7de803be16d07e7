r"""Hertz check on a solid hemisphere
=================================

Hertz check on a solid hemisphere (R = 20 mm, C10 = 0.3 MPa): P/P_Hertz along loading.

P_Hertz = (4/3) E* sqrt(R) delta^1.5 with E* = 8 C10.  The FE body is finite with its top
face held, so P/P_Hertz grows like 1 + 0.7 a/R (an independent solution); a/sqrt(R delta)
shows how well the mesh locates the contact edge.

    python examples/ex02_hertz_table.py [coarse|default|fine]
"""
import sys

import numpy as np

from shell_adhesion.solver.case import solve_loading


def table(mesh="default", interface="no_slip", delta_max=0.0026):
    """Rows (a/R, delta/R, P/P_Hertz, a/sqrt(R delta)) at corner-node contact events."""
    d, path = solve_loading(1.0, 1.0, interface, mesh, delta_max)
    rows = []
    for s in path.events[1:]:
        if d.capmesh.outer_corner[max(s.held)]:
            rows.append((s.a, s.delta, s.P / (4 / 3 * 8 * s.delta ** 1.5), s.a / np.sqrt(s.delta)))
    return np.array(rows)


if __name__ == "__main__":
    mesh = sys.argv[1] if len(sys.argv) > 1 else "coarse"
    for interface in ("no_slip", "frictionless"):
        print(f"{interface} ({mesh} mesh):  a/R   P/P_Hertz  1+0.7a/R  a/sqrt(R delta)")
        for a, delta, ratio, a_ratio in table(mesh, interface)[1::2]:
            print(f"        {a:.4f}  {ratio:.4f}     {1 + 0.7 * a:.4f}    {a_ratio:.4f}")
