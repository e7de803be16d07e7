"""Identity of stored results: canonical JSON and its sha256 (the one fingerprint function).

A key is a JSON-able mapping of everything that changes a result.  Floats are written
with 12 significant digits, so 0.15 and 0.15000000000000002 are the same key; mappings
are sorted, so the order of fields never matters.

`pathset_key` is the key of one set of FE paths (DESIGN.md section 3): the dimensionless
shell, the interface, the mesh, how far the paths go (delta_max / R, the largest
gamma / (C10 R) they serve), the solver tolerances and relaxation rule, the package
version and a hash of the solver's source.  C10, R and gamma are not in it.
"""
from dataclasses import asdict
from functools import lru_cache
import hashlib
import json
import math
from pathlib import Path

import numpy as np

LAYOUT = 2          # version of the stored path-set file layout (catalogue.pathfile)
AT_LEAST = ("delta_max_over_R", "gamma_max_hat")   # a stored set with larger values serves


def _canonical(obj):
    if isinstance(obj, dict):
        return {str(k): _canonical(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_canonical(v) for v in obj]
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        x = float(obj)
        if not math.isfinite(x):
            raise ValueError(f"a fingerprinted key cannot hold {x!r}")
        return float(f"{x:.12g}")
    if obj is None or isinstance(obj, str):
        return obj
    raise TypeError(f"cannot fingerprint a {type(obj).__name__}")


def canonical_json(key) -> str:
    """The canonical JSON text of a key (sorted, compact, 12-digit floats)."""
    return json.dumps(_canonical(key), sort_keys=True, separators=(",", ":"),
                      ensure_ascii=True, allow_nan=False)


def fingerprint(key) -> str:
    """sha256 (hex) of the canonical JSON of `key`."""
    return hashlib.sha256(canonical_json(key).encode("ascii")).hexdigest()


def family(key) -> str:
    """Fingerprint of a path-set key without its AT_LEAST fields (sets that may serve it)."""
    return fingerprint({k: v for k, v in key.items() if k not in AT_LEAST})


@lru_cache(maxsize=1)
def solver_source_sha256() -> str:
    """sha256 over the solver package's Python sources (names and contents)."""
    from shell_adhesion import solver
    h = hashlib.sha256()
    for p in sorted(Path(solver.__file__).parent.glob("*.py")):
        h.update(p.name.encode() + b"\0" + p.read_bytes() + b"\0")
    return h.hexdigest()


def pathset_key(t_over_R, h_over_R, interface, mesh, delta_max_over_R, gamma_max_hat,
                settings=None) -> dict:
    """Key of the FE path set of one dimensionless shell (validated names and values)."""
    from shell_adhesion import solver
    from shell_adhesion.solver import case
    from shell_adhesion.solver.mesh import mesh_spec
    settings = settings if settings is not None else solver.Settings()
    return {
        "kind": "shell-adhesion path set",
        "layout": LAYOUT,
        "t_over_R": float(t_over_R),
        "h_over_R": float(h_over_R),
        "interface": str(interface),
        "mesh": str(mesh),
        "mesh_spec": asdict(mesh_spec(mesh)),
        "delta_max_over_R": float(delta_max_over_R),
        "gamma_max_hat": float(gamma_max_hat),
        "settings": asdict(settings),
        "relaxation_rule": {"G_SAFETY": case.G_SAFETY, "STEPS_PER_PATH": case.STEPS_PER_PATH},
        "version": solver.__version__,
        "solver_source": solver_source_sha256(),
    }
