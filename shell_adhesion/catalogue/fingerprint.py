"""Identity of stored results: canonical JSON and its sha256 (the one fingerprint function).

A key is a JSON-able mapping of everything that changes a result (study.keys makes the
keys of FE path sets).  Floats are written with 12 significant digits, so 0.15 and
0.15000000000000002 are the same key; mappings are sorted, so the order of fields never
matters.
"""
import hashlib
import json
import math

import numpy as np

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
    """Fingerprint of a key without its AT_LEAST fields (stored sets that may serve it)."""
    return fingerprint({k: v for k, v in key.items() if k not in AT_LEAST})
