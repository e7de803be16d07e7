"""The persistent store of solved FE path sets (and the record of study runs).

One netCDF file per path set, named by its fingerprint (sha256 of the canonical JSON of
everything that changes the result), and an SQLite index of parameters, status, timings
and provenance.  See `catalogue.store` for the folder layout and the trust rule.
"""
from .fingerprint import canonical_json, family, fingerprint, pathset_key
from .pathfile import CorruptFile, write_atomic
from .store import (COLUMNS, ENV_VAR, Catalogue, Entry, default_dir, format_entries,
                    list_entries)

__all__ = ["canonical_json", "family", "fingerprint", "pathset_key", "CorruptFile",
           "write_atomic", "COLUMNS", "ENV_VAR", "Catalogue", "Entry", "default_dir",
           "format_entries", "list_entries"]
