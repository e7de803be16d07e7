"""The slices of a results cube that the tables and figures read: the study's base solid
of a cube that sweeps a material ratio, the base pressure and C10 of a closed cavity's
cube, and the label of a solid."""
import xarray as xr

from shell_adhesion.cube import DIMS, IN_MPA, RATIOS


def base_material(ds: xr.Dataset) -> xr.Dataset:
    """The cube at the study's base solid: a swept material ratio (a dimension such as
    C01_over_C10) at its value in the material block, else its first value."""
    at = {}
    for d in ds["status"].dims:
        if d not in DIMS:
            v = ds.attrs.get(f"material_{d}")
            at[d] = v if v is not None and v in ds[d].values else ds[d].values[0]
    return ds.sel(at) if at else ds


def base_cavity(ds: xr.Dataset) -> xr.Dataset:
    """A closed-cavity cube as the figures read it: a swept p_kPa at its base value (else
    its first), and the per-shell variables that gained C10 (attribute cavity_per_C10)
    at the base C10 (else the first)."""
    if "cavity_per_C10" not in ds.attrs:
        return ds
    if "p_kPa" in ds.dims:
        p = ds.attrs.get("cavity_p_kPa")
        ds = ds.sel(p_kPa=p if p is not None and p in ds["p_kPa"].values
                    else ds["p_kPa"].values[0])
    C10 = ds.attrs.get("base_C10_MPa")
    C10 = C10 if C10 is not None and C10 in ds["C10"].values else ds["C10"].values[0]
    names = [n for n in str(ds.attrs["cavity_per_C10"]).split() if n in ds.variables]
    at = {n: ds[n].sel(C10=C10, drop=True).variable for n in names}
    coords = {n: v for n, v in at.items() if n in ds.coords}
    ds = ds.drop_vars(names).assign({n: v for n, v in at.items() if n not in coords})
    return ds.assign_coords(coords)


def material_label(ds: xr.Dataset) -> tuple:
    """(text, paper_solid): the solid of a cube, or of its slice at one value of each swept
    ratio, e.g. "mooney_rivlin (C01_over_C10 = 0.2)"; paper_solid is True for the
    incompressible neo-Hookean solid (any model whose coefficients reduce to it)."""
    a = ds.attrs
    model = a.get("material_model", "neo_hooke")
    values = {k.removeprefix("material_"): float(v) for k, v in a.items()
              if k.startswith("material_") and k != "material_model"}
    swept = {d: float(ds[d]) for d in (*RATIOS, *IN_MPA) if d in ds.coords and ds[d].ndim == 0}
    values.update(swept)
    if swept or "material" not in a:
        text = model + (f" ({', '.join(f'{k} = {v:g}' for k, v in values.items())})"
                        if values else "")
    else:
        text = a["material"]
    reduces = model in ("neo_hooke", "mooney_rivlin", "yeoh") and not any(
        v for k, v in values.items() if k not in ("C10_MPa", "Jm"))
    return text, reduces
