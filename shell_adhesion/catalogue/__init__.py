"""The persistent store of computed Datasets (FE path sets) and the record of study runs.

One netCDF file per stored Dataset, named by its fingerprint (sha256 of the canonical JSON
of the key the caller computes: everything that changes the result), and an SQLite index
of parameters, status, timings and provenance.  See `catalogue.store` for the folder
layout and the trust rule.  This package imports nothing from the solver.
"""
from .fingerprint import canonical_json, family, fingerprint
from .files import CorruptFile, write_atomic
from .store import (COLUMNS, ENV_VAR, Catalogue, Claim, Entry, default_dir,
                    format_entries, list_entries)

__all__ = ["canonical_json", "family", "fingerprint", "CorruptFile", "write_atomic",
           "COLUMNS", "ENV_VAR", "Catalogue", "Claim", "Entry", "default_dir",
           "format_entries", "list_entries"]
