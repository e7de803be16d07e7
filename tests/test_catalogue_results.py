"""Cubes and products kept in the catalogue (catalogue.results): served only when every
file matches the sha256 its manifest records; a store cut short (files without their
manifest), an altered or truncated file, or a name leaving the folder is not served."""
from shell_adhesion.catalogue import results


def _made(tmp_path):
    src = tmp_path / "made"
    (src / "t").mkdir(parents=True, exist_ok=True)
    (src / "t" / "cases.csv").write_text("a,b\n1,2\n")
    (src / "fig.png").write_bytes(b"\x89PNG fake")
    return {"tables/cases.csv": src / "t" / "cases.csv", "figures/fig.png": src / "fig.png"}


def test_products_served_as_stored(tmp_path):
    results.store_products(tmp_path / "cat", "k", _made(tmp_path), {"fig6": "no data"})
    files, skipped = results.fetch_products(tmp_path / "cat", "k")
    assert files == {"tables/cases.csv": b"a,b\n1,2\n", "figures/fig.png": b"\x89PNG fake"}
    assert skipped == {"fig6": "no data"}
    assert results.fetch_products(tmp_path / "cat", "other") is None


def test_products_not_served_when_altered_or_cut_short(tmp_path):
    cat = tmp_path / "cat"
    results.store_products(cat, "k", _made(tmp_path), {})
    figure = cat / "products" / "k" / "figures" / "fig.png"
    figure.write_bytes(b"\x89PNG fakf")                             # altered, same size
    assert results.fetch_products(cat, "k") is None
    results.store_products(cat, "k", _made(tmp_path), {})          # stored again: served
    assert results.fetch_products(cat, "k") is not None
    figure.unlink()                                                 # a file gone
    assert results.fetch_products(cat, "k") is None
    results.store_products(cat, "k", _made(tmp_path), {})
    (cat / "products" / "k" / "manifest.json").unlink()             # cut short
    assert results.fetch_products(cat, "k") is None
    (cat / "products" / "k" / "manifest.json").write_text('{"files": {"../x": "0"}}')
    assert results.fetch_products(cat, "k") is None                 # leaves its folder
    assert not [p for p in cat.rglob("*") if ".tmp" in p.name]      # nothing half-written


def test_cube_served_only_whole(tmp_path):
    cube = tmp_path / "paper.nc"
    cube.write_bytes(b"CDF netCDF bytes" * 100)
    results.store_cube(tmp_path / "cat", "inputs", cube, "content")
    assert results.fetch_cube(tmp_path / "cat", "inputs") == (cube.read_bytes(), "content")
    assert results.fetch_cube(tmp_path / "cat", None) is None
    kept = tmp_path / "cat" / "cubes" / "inputs.nc"
    kept.write_bytes(kept.read_bytes()[:800])                       # truncated
    assert results.fetch_cube(tmp_path / "cat", "inputs") is None
