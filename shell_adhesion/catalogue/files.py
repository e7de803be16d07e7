"""Stored Datasets as netCDF files: written atomically (shell_adhesion.atomic), read from one
in-memory copy, so the bytes checked against the index's sha256 are the bytes decoded.

The catalogue does not know what a Dataset holds: it adds the attributes `fingerprint`
and `key` (the canonical JSON of the key it is stored under) and checks the fingerprint
when reading.
"""
import hashlib
from pathlib import Path

import netCDF4
import xarray as xr

from shell_adhesion.atomic import atomic_path


class CorruptFile(Exception):
    """A stored file is missing, truncated, altered or not the expected Dataset."""


def write_atomic(ds: xr.Dataset, path, encoding=None) -> tuple:
    """Write `ds` to `path` atomically (shell_adhesion.atomic); returns (sha256 hex, size in
    bytes) of the bytes written."""
    # with a dask.distributed client active, xarray would take its write lock on the
    # scheduler (a round trip per file, and a hang or an error at exit once the scheduler
    # is gone): the file is local, a local lock is right
    import dask                 # on use: a run that writes nothing does not import it
    with atomic_path(path) as tmp, dask.config.set(scheduler="synchronous"):
        ds.to_netcdf(tmp, engine="netcdf4", format="NETCDF4", encoding=encoding)
        data = Path(tmp).read_bytes()
    return hashlib.sha256(data).hexdigest(), len(data)


def write(path, ds: xr.Dataset, fp: str, key_json: str) -> tuple:
    """Store `ds` at `path` atomically with float variables compressed, marked with its
    fingerprint `fp` and key: (sha256 hex, size in bytes)."""
    ds = ds.copy()
    ds.attrs.update(fingerprint=fp, key=key_json)
    enc = {v: {"zlib": True, "complevel": 4} for v in ds.data_vars
           if ds[v].dtype.kind == "f" and ds[v].size > 0}
    return write_atomic(ds, path, enc)


def matches(path, sha256: str) -> bool:
    """The bytes at `path` have digest `sha256` (read, not decoded)."""
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest() == sha256
    except OSError:
        return False


def read(path, sha256: str, fp: str) -> xr.Dataset:
    """The Dataset stored at `path` (loaded; without the fingerprint and key attributes);
    CorruptFile unless its bytes match `sha256` and its fingerprint is `fp`."""
    try:
        data = Path(path).read_bytes()
    except OSError as e:
        raise CorruptFile(f"{path}: {e.strerror or e}") from None
    if hashlib.sha256(data).hexdigest() != sha256:
        raise CorruptFile(f"{path}: checksum mismatch")
    try:
        nc = netCDF4.Dataset("stored.nc", mode="r", memory=data)
        try:
            ds = xr.open_dataset(xr.backends.NetCDF4DataStore(nc)).load()
        finally:
            nc.close()
    except Exception as e:      # any decoding failure means the file cannot be trusted
        raise CorruptFile(f"{path}: cannot be read ({type(e).__name__}: {e})") from None
    if ds.attrs.pop("fingerprint", None) != fp:
        raise CorruptFile(f"{path}: not the stored Dataset {fp[:12]}")
    ds.attrs.pop("key", None)
    return ds
