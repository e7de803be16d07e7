"""The study's results as one labelled xarray Dataset written as netCDF (the names of the
layout are in `shell_adhesion.cube`, which the readers share).

Dimensions ``C10`` (MPa), ``t_over_R``, ``h_over_R``, ``gamma`` (J/m^2): a full cube over
the union of the study's values.  Only the requested points (the base, each sweep line,
the grid) are evaluated; the others are NaN with ``status`` "not requested".  Units:
lengths mm, forces N, energies mJ (N mm); P > 0 compression, delta > 0 approach.

- pull-off (C10, t_over_R, h_over_R, gamma): P_star, delta_star, a_star (fixed load),
  P_dagger, delta_dagger, a_dagger (fixed grips), a0 (P = 0), eta (eq. 3), status, reason;
- equilibrium curves (..., point): delta_eq, P_eq and stability flags along the coordinate
  a_eq_mm, NaN-padded along ``point`` (the points where G = gamma, increasing a);
- loading curves (t_over_R, h_over_R, loading_state): loading_a along the coordinate
  loading_delta_mm, and with C10 (exact scaling, every C10 of the axis) loading_P, loading_U;
- relaxation curves (t_over_R, h_over_R, relaxation[, relaxation_state]): one path per held
  contact radius, the coordinate relaxation_a_mm, relaxation_used, and with C10
  relaxation_P and relaxation_U along the coordinate relaxation_delta_mm;
- deformed states (t_over_R, h_over_R, profile | stress_map, ...): profile_* (outer and
  inner surfaces of a few loading states and of the widest relaxation path), map_* (deformed
  nodes, von Mises stress with C10, plotting triangles);
- per shell (t_over_R, h_over_R): pathset_fingerprint, the catalogue entry of the FE
  paths used, and gamma_max_hat, the largest gamma / (C10 R) they serve.

Coordinates: the dimension coordinates keep DESIGN.md's names (C10, t_over_R, h_over_R,
gamma); non-index companions carry the unit in their name (C10_MPa, gamma_J_m2, t_mm, h_mm,
gamma_hat) and so do the curves' coordinates (a_eq_mm, loading_delta_mm, relaxation_a_mm,
relaxation_delta_mm), so that ``ds.P_star.sel(C10=0.3, t_over_R=0.15, h_over_R=1).plot(
x="gamma_J_m2")`` and ``ds.P_eq.sel(C10=0.3, t_over_R=0.15, h_over_R=1, gamma=30).plot(
x="a_eq_mm")`` work.  Unit strings are read by UDUNITS (CF) and by
pint's default registry alike.  The study is stored as plain attributes (R_mm, base_C10_MPa,
sweep_gamma_J_m2, ..., see `study_attrs`), from which `study_of` rebuilds the study file's
dictionary.

A closed cavity (the study's ``cavity:`` block) makes every C10 (and every p_kPa) its own
FE path set: the cube is then the cubes of each (C10[, p_kPa]) concatenated, so the per-shell
and per-state variables (loading and relaxation curves, deformed states, fingerprints) gain
the ``C10`` dimension (and ``p_kPa``, a dimension when swept).  It adds loading_V_mm3,
loading_p_kPa, relaxation_V_mm3, relaxation_p_kPa (the enclosed volume and the gauge
pressure along the curves), cavity_apex_uz_mm (the free pressurised apex's displacement
before the first touch, z up) and the attributes cavity_mode, cavity_p_kPa (unless swept),
cavity_p_atm_kPa, cavity_p0_kPa and cavity_gas_exponent (sealed).

``xarray.open_dataset("results/<name>.nc")`` is all a reader needs; the file passes the
CF-1.8 compliance checker without a high-priority failure.
"""
from dataclasses import asdict
import hashlib
from datetime import datetime, timezone
from pathlib import Path

import numpy as np
import xarray as xr

from shell_adhesion import solver
from shell_adhesion.catalogue import write_atomic
from shell_adhesion.cube import (CURVE_COORDS, CURVES, DIMS, GAMMA_UNITS, PULL_OFF, STATUS,
                                 study_attrs)
from shell_adhesion.solver import case, request
from shell_adhesion.solver.cavity import P_ATM_KPA
from shell_adhesion.solver.error_bars import (ORDER, assumed_order, coarsest_usable,
                                               curve_error, error_bar, observed_order,
                                               refines_through_thickness)
from shell_adhesion.solver.material import NEO_HOOKE
from shell_adhesion.solver.mesh import mesh_spec
from shell_adhesion.solver.scaling import energy_mJ, force_N, gamma_hat, length_mm
from shell_adhesion.theory import eta_of

from .config import IN_MPA
from .keys import solver_source_sha256
from .plan import Plan

INDEX_DTYPE = np.int32          # CF-1.8 has no 64-bit integers
def _attrs(units, long_name, **more):
    return dict(units=units, long_name=long_name, **more)


def _evaluate(ps, surface, C10, R, t, gamma, material=NEO_HOOKE):
    """Pull-off values (dimensional) and the equilibrium curve of one point (eta with the
    material's small-strain modulus)."""
    eq, po = ps.pull_off(gamma_hat(gamma, C10, R), surface)
    conv = dict(force=lambda x: force_N(x, C10, R), length=lambda x: length_mm(x, R))
    values = {k: conv[kind](getattr(po, k)) for k, (_, _, kind) in PULL_OFF.items()}
    values["eta"] = eta_of(values["P_star"], R, t * R, C10, gamma, material)
    values["note"] = po.note            # why the fixed-grips values are not given (if not)
    curve = dict(a_eq_mm=length_mm(eq.a, R), delta_eq=length_mm(eq.delta, R),
                 P_eq=force_N(eq.P, C10, R),
                 stable_fixed_load=np.asarray(eq.stable_fixed_load, dtype=float),
                 stable_fixed_grips=np.asarray(eq.stable_fixed_grips, dtype=float))
    return values, curve


def build(plan: Plan, served: dict, failed: dict, history: str = "") -> xr.Dataset:
    """The results cube of a planned study.

    served: (t/R, h/R[, Material]) -> (fingerprint, PathSet) for the shells with FE paths;
    failed: (t/R, h/R[, Material]) -> reason for the shells whose FE paths could not be
    computed.  A key ending in "coarser" (after the Material) is a shell's error-bar
    companion on the next coarser mesh (study.plan.served_key): its values give the
    `<name>_error` variables (solver.error_bars; NaN where it has none).  A study sweeping material ratios gets one more dimension per swept ratio
    (named as in the study file, e.g. C01_over_C10): the cubes of each solid, concatenated
    (curves NaN-padded to the longest).
    """
    if plan.ratio_axes:
        return _build_swept(plan, served, failed, history)
    material = plan.shells[0].material if plan.shells else NEO_HOOKE
    if plan.cavities:
        return _build_cavity(plan, served, failed, history, material)
    served = {_short(k): v for k, v in served.items() if len(k) == 2 or k[2] == material}
    failed = {_short(k): v for k, v in failed.items() if len(k) == 2 or k[2] == material}
    ds = _build(plan, served, failed, history, material)
    if material != NEO_HOOKE or plan.study.material:
        ds.attrs.update(_material_attrs(plan, material))
    return ds


def _material_attrs(plan: Plan, material) -> dict:
    study = plan.study
    C10 = study.base.get("C10_MPa")
    text = material.coefficients(C10) if C10 is not None else material.coefficients()
    fixed = {f"material_{r}": v for r, v in study.material.items() if r != "model"}
    return dict(material_model=study.model,
                material=text if not plan.ratio_axes    # text names the model
                else f"{study.model} (swept: {', '.join(plan.ratio_axes)})",
                title=f"{study.description or f'shell-adhesion study {study.name}'}; "
                      f"material " + (text if not plan.ratio_axes else study.model),
                source=_global_attrs(plan, "")["source"].replace(
                    "incompressible neo-Hookean", f"{study.model} hyperelastic"),
                **fixed)


def _build_swept(plan: Plan, served: dict, failed: dict, history: str) -> xr.Dataset:
    """Cubes of each swept solid stacked along the solids, then unstacked into one
    dimension per swept ratio (combinations not requested are NaN / "not requested")."""
    names = tuple(plan.ratio_axes)
    combos = sorted(plan.materials)
    cubes = []
    for values in combos:
        m = plan.materials[values]
        cubes.append(_build(plan.for_ratios(values),
                            {_short(k): v for k, v in served.items() if k[2] == m},
                            {_short(k): v for k, v in failed.items() if k[2] == m}, history, m))
    ds = xr.concat(cubes, dim="_material", join="outer", data_vars="all",
                   coords="different", compat="equals", combine_attrs="override")
    ds = ds.assign_coords({n: ("_material", np.array([v[j] for v in combos], dtype=float))
                           for j, n in enumerate(names)})
    if len(names) == 1:
        ds = ds.swap_dims({"_material": names[0]})
    else:
        ds = ds.set_index(_material=list(names)).unstack("_material")
    status = ds["status"]
    ds["status"] = status.where(status.notnull(), "not requested").astype(object)
    ds["status"].attrs = status.attrs
    for k in ("reason", "loading_stopped_by", "error_note"):
        if k not in ds:
            continue
        attrs = ds[k].attrs
        ds[k] = ds[k].where(ds[k].notnull(), "").astype(object)
        ds[k].attrs = attrs
    for n in names:
        ds[n].attrs = _attrs("1", _RATIO_NAMES[n])
    for k in plan.study.in_MPa:         # the coefficients the file gives in MPa, as given
        r = IN_MPA[k]
        if r in names:
            C10 = ds["C10"]
            ds = ds.assign_coords({k: ds[r] / C10 if k == "D1_per_MPa" else ds[r] * C10})
            ds[k].attrs = _attrs(*_MPA_NAMES[k])
    ds.attrs.update(_material_attrs(plan, plan.materials[combos[0]]))
    return ds


# -- closed cavities ---------------------------------------------------------------------

def _build_cavity(plan: Plan, served: dict, failed: dict, history: str, material) -> xr.Dataset:
    """A closed cavity: the cube of each (C10, swept cavity values) from its own path sets
    (served keys (t/R, h/R, Material, Cavity)), concatenated along C10, then along the
    swept cavity parameters (combinations not requested are NaN / "not requested")."""
    names = tuple(plan.cavity_axes or ())
    groups = {}
    for C10, values in plan.cavity_groups():
        sub = plan.for_cavity(C10, values)
        cavity = sub.shells[0].cavity
        pick = lambda d: {k[:2] + k[4:]: v for k, v in d.items()   # k[4:]: ("coarser",)
                          if len(k) > 3 and k[2] == material and k[3] == cavity}
        here = pick(served)
        cube = _build(sub, here, pick(failed), history, material)
        cube = cube.assign(_cavity_curves(sub, here, C10))
        per_C10 = sorted(v for v in cube.variables if "C10" not in cube[v].dims
                         and ({"t_over_R", "h_over_R"} & set(cube[v].dims)))
        groups.setdefault(values, []).append(cube)
    concat = dict(join="outer", data_vars="all", compat="equals", combine_attrs="override")
    curve_coords = [c for c in ("loading_delta_mm", "relaxation_a_mm", "relaxation_delta_mm")]
    cubes = [xr.concat(g, dim="C10", coords=[c for c in curve_coords if c in g[0].coords],
                       **concat) for g in groups.values()]
    if names:
        C10_attrs, gh_attrs = cubes[0]["C10_MPa"].attrs, cubes[0]["gamma_hat"].attrs
        cubes = [c.drop_vars(["C10_MPa", "gamma_hat"]) for c in cubes]
        listed = [c for c in curve_coords + ["a_eq_mm"] if c in cubes[0].coords]
        dim = xr.Variable(names, np.array([v[0] for v in groups], dtype=float),
                          _attrs("kPa", "prescribed gauge pressure p in the cavity "
                                        "(> 0 inflates)"))
        ds = xr.concat(cubes, dim=xr.DataArray(dim, dims=names, name=names[0]),
                       coords=listed, **concat)
        C10s = ds["C10"].values
        ds = ds.assign_coords(
            C10_MPa=("C10", C10s, C10_attrs),
            gamma_hat=(("C10", "gamma"), gamma_hat(ds["gamma"].values[None, :],
                                                   C10s[:, None], plan.study.R_mm), gh_attrs))
        for k, fill in (("status", "not requested"), ("reason", ""), ("error_note", "")):
            if k not in ds:
                continue
            attrs = ds[k].attrs
            ds[k] = ds[k].where(ds[k].notnull(), fill).astype(object)
            ds[k].attrs = attrs
    else:
        ds = cubes[0]
    ds.attrs.update(_cavity_attrs(plan))
    # the per-shell variables that gained C10 (the figures read them at one C10)
    ds.attrs["cavity_per_C10"] = " ".join(v for v in per_C10 if "C10" in ds[v].dims)
    if material != NEO_HOOKE or plan.study.material:
        ds.attrs.update(_material_attrs(plan, material))
    return ds


def _cavity_attrs(plan: Plan) -> dict:
    """The cavity block in kPa with its defaults (a swept p_kPa is a coordinate)."""
    block = plan.study.cavity
    mode = block["mode"]
    out = dict(cavity_mode=mode, cavity_p_atm_kPa=float(block.get("p_atm_kPa", P_ATM_KPA)))
    if mode == "pressure" and "p_kPa" in block:
        out["cavity_p_kPa"] = float(block["p_kPa"])
    if mode == "sealed":
        out.update(cavity_p0_kPa=float(block.get("p0_kPa", 0.0)),
                   cavity_gas_exponent=float(block.get("gas_exponent", 1.0)))
    return out


def _cavity_curves(plan: Plan, served: dict, C10: float) -> dict:
    """Volume and gauge pressure along the loading and relaxation curves, and the apex
    displacement before the first touch, of the shells of one C10 (padded as _build)."""
    study, R, ax = plan.study, plan.study.R_mm, plan.axes
    index = {f: {v: i for i, v in enumerate(ax[f])} for f in ("t_over_R", "h_over_R")}
    shells = (len(ax["t_over_R"]), len(ax["h_over_R"]))
    at = {(index["t_over_R"][k[0]], index["h_over_R"][k[1]]): ps
          for k, (_, ps) in served.items() if len(k) == 2}     # not the error-bar companions
    mm3, kPa = R ** 3, C10 * 1e3
    S = ("t_over_R", "h_over_R")
    lift = np.full(shells, np.nan)
    for j, ps in at.items():
        lift[j] = -ps.stats.get("cavity_lift", np.nan) * R
    out = {"cavity_apex_uz_mm": (S, lift, _attrs(
        "mm", "apex displacement u_z of the free pressurised shell before the first touch "
              "(z up: < 0 it bulged toward the plane); delta is measured from that touch"))}
    if study.outputs.loading_curves:
        n = max([len(ps.loading_delta) for ps in at.values()], default=0)
        V, p = np.full(shells + (n,), np.nan), np.full(shells + (n,), np.nan)
        for j, ps in at.items():
            V[j][:len(ps.loading_V)], p[j][:len(ps.loading_p)] = ps.loading_V, ps.loading_p
        L = (*S, "loading_state")
        out["loading_V_mm3"] = (L, V * mm3, _attrs("mm^3", "cavity volume V on loading"))
        out["loading_p_kPa"] = (L, p * kPa, _attrs("kPa", "cavity gauge pressure p on loading"))
    if study.outputs.relaxation_curves:
        width = (max([len(r.delta) for ps in at.values() for r in ps.relaxations], default=0),)
        K = (*S, "relaxation", "relaxation_state")
        for k, scale, name, what in (("V", mm3, "mm3", "cavity volume V"),
                                     ("p", kPa, "kPa", "cavity gauge pressure p")):
            arr = _padded(shells, {j: [getattr(r, k) for r in ps.relaxations]
                                   for j, ps in at.items()}, width)
            out[f"relaxation_{k}_{name}"] = (K, arr * scale, _attrs(
                "mm^3" if k == "V" else "kPa",
                f"{what} along the relaxation at fixed contact radius"))
    return out


_RATIO_NAMES = {"C01_over_C10": "Mooney-Rivlin ratio C01 / C10",
                "C20_over_C10": "Yeoh ratio C20 / C10", "C30_over_C10": "Yeoh ratio C30 / C10",
                "Jm": "Gent limit Jm of I1bar - 3",
                "D1_times_C10": "compressibility D1 C10 (0: incompressible)"}


_MPA_NAMES = {"C01_MPa": ("MPa", "Mooney-Rivlin C01 (C01_over_C10 x C10)"),
              "C20_MPa": ("MPa", "Yeoh C20 (C20_over_C10 x C10)"),
              "C30_MPa": ("MPa", "Yeoh C30 (C30_over_C10 x C10)"),
              "D1_per_MPa": ("1/MPa", "compressibility D1 (D1_times_C10 / C10)")}
def _short(key) -> tuple:
    """(t/R, h/R) of a served key, with "coarser" kept for an error-bar companion."""
    return key[:2] + tuple(key[3:])


def _errors(values, coarser, coarsest=None, observable=True, order=ORDER) -> dict:
    """`<name>_error` of each pull-off value and eta from the next coarser mesh's values
    (and the one after it's: Richardson where the three converge and the family's steps
    are `observable`; from two meshes the bar assumes `order`), and `<name>_order`, the
    order observed on the three meshes (NaN where an assumed order is used:
    solver.error_bars)."""
    out = {}
    for k, v in values.items():
        c3 = coarsest[k] if coarsest else None
        out[f"{k}_error"] = (float(error_bar(v, coarser[k], c3, observable, order)) if coarser
                             else np.nan)
        out[f"{k}_order"] = (float(observed_order(v, coarser[k], c3, observable))
                             if coarser and coarsest else np.nan)
    return out


def _build(plan: Plan, served: dict, failed: dict, history: str, material) -> xr.Dataset:
    coarser = {k[:2]: v for k, v in served.items() if len(k) == 3 and k[2] == "coarser"}
    coarsest = {k[:2]: v for k, v in served.items() if len(k) == 3 and k[2] == "coarsest"}
    served = {k: v for k, v in served.items() if len(k) == 2}
    failed = {k: v for k, v in failed.items() if len(k) == 2}
    study = plan.study
    R = study.R_mm
    ax = plan.axes
    index = {f: {v: i for i, v in enumerate(ax[f])} for f in ax}
    shape = tuple(len(ax[f]) for f in ("C10_MPa", "t_over_R", "h_over_R", "gamma_J_m2"))

    surfaces, surface_errors = {}, {}
    for th, (_, ps) in served.items():
        try:
            surfaces[th] = ps.surface()
        except Exception as e:      # too few usable paths to build G at all
            surface_errors[th] = f"energy surface: {type(e).__name__}: {e}"
    companion_surfaces = {}
    for level, sets in (("coarser", coarser), ("coarsest", coarsest)):
        for th, (_, ps) in sets.items():
            try:
                companion_surfaces[level, th] = ps.surface()
            except Exception:           # no error bars (of that level) for this shell
                pass

    def companion(level, sets, th, C10, gamma, t):
        """The pull-off values on the companion mesh `level`, or None, and why not."""
        if th not in sets or (level, th) not in companion_surfaces:
            return None, f"the {level} mesh's paths are not available"
        try:
            return _evaluate(sets[th][1], companion_surfaces[level, th], C10, R, t, gamma,
                             material)[0], ""
        except ValueError as e:         # out of its range
            return None, f"the {level} mesh: {e}"

    status = np.full(shape, "not requested", dtype=object)
    reason = np.full(shape, "", dtype=object)
    notes = np.full(shape, "", dtype=object)
    results = {}
    for C10, t, h, gamma in plan.points:
        i = (index["C10_MPa"][C10], index["t_over_R"][t], index["h_over_R"][h],
             index["gamma_J_m2"][gamma])
        if (t, h) in failed:
            status[i], reason[i] = "solver failed", failed[t, h]
        elif (t, h) in surface_errors:
            status[i], reason[i] = "out of range", surface_errors[t, h]
        else:
            try:
                results[i] = _evaluate(served[t, h][1], surfaces[t, h], C10, R, t, gamma,
                                       material)
                status[i], reason[i] = "ok", results[i][0].pop("note")
                if plan.study.error_bars:
                    (c2, why2), (c3, why3) = (companion(level, sets, (t, h), C10, gamma, t)
                                              for level, sets in (("coarser", coarser),
                                                                  ("coarsest", coarsest)))
                    results[i][0].update(_errors(
                        results[i][0], c2, c3 if coarsest_usable(t, study.mesh) else None,
                        refines_through_thickness(t, study.mesh), assumed_order(t, study.mesh)))
                    notes[i] = "; ".join(w for w in (why2, why3) if w)
            except ValueError as e:     # shell_adhesion.energy.OutOfRange and gamma > gamma_max
                status[i], reason[i] = "out of range", str(e)

    n_point = max([len(c["a_eq_mm"]) for _, c in results.values()], default=0)
    n_load = max([len(ps.loading_delta) for _, ps in served.values()], default=0)
    names = (*PULL_OFF, "eta")
    values = {k: np.full(shape, np.nan)
              for k in names + (tuple(f"{n}_{e}" for n in names for e in ("error", "order"))
                                if study.error_bars else ())}
    curves = {k: np.full(shape + (n_point,), np.nan) for k in CURVES}
    inverted = np.full(shape, np.nan)
    for i, (v, c) in results.items():
        for k, x in v.items():
            values[k][i] = x
        ps = served[ax["t_over_R"][i[1]], ax["h_over_R"][i[2]]][1]
        inverted[i] = float(ps.inverted([v["a_star"] / R, v["a_dagger"] / R]).any())
        for k, x in c.items():
            curves[k][i][:len(x)] = x

    data = {k: (DIMS, values[k], _attrs(u, ln)) for k, (u, ln, _) in PULL_OFF.items()}
    data["eta"] = (DIMS, values["eta"], _attrs(
        "1", "eta of eq. 3: |P*| / [gamma^4 R^4 (1 - nu^2) / (E t^2)]^(1/3)"))
    if study.error_bars:
        for k in names:
            units = PULL_OFF[k][0] if k in PULL_OFF else "1"
            data[f"{k}_error"] = (DIMS, values[f"{k}_error"], _attrs(
                units, f"discretisation error estimate of {k} (the next two coarser meshes, "
                       "solver.error_bars; NaN: not available)"))
            data[f"{k}_order"] = (DIMS, values[f"{k}_order"], _attrs(
                "1", f"order of convergence of {k} observed on three meshes, used by its "
                     "error estimate (NaN: not observed, order 1 assumed with factor 3)"))
    if study.error_bars:
        data["error_note"] = (DIMS, notes, _attrs(
            "1", "why an ok point's error bars are missing, or from two meshes only (empty: "
                 "from three)"))
    data["status"] = (DIMS, status, _attrs(
        "1", "evaluation status of the point", comment="one of: " + "; ".join(STATUS)))
    data["reason"] = (DIMS, reason, _attrs("1", "why a point is not ok, or why its fixed-grips "
                                                "values are not given (empty: all given)"))
    C10s, gammas = np.array(ax["C10_MPa"]), np.array(ax["gamma_J_m2"])
    data["gamma_hat"] = (("C10", "gamma"), gamma_hat(gammas[None, :], C10s[:, None], R),
                         _attrs("1", "dimensionless work of adhesion gamma / (C10 R)"))
    if study.outputs.equilibrium_curves:
        for k, (u, ln) in CURVES.items():
            data[k] = ((*DIMS, "point"), curves[k], _attrs(u, ln))

    shells = (len(ax["t_over_R"]), len(ax["h_over_R"]))
    fps = np.full(shells, "", dtype=object)
    gmax = np.full(shells, np.nan)
    even = np.full(shells, np.nan)
    load = {k: np.full(shells + (n_load,), np.nan) for k in ("delta", "a", "P", "U")}
    for (t, h), (fp, ps) in served.items():
        j = (index["t_over_R"][t], index["h_over_R"][h])
        fps[j], gmax[j] = fp, ps.gamma_max
        even[j] = mesh_spec(ps.mesh, ps.uniform).uniform
        n = len(ps.loading_delta)
        for k in load:
            load[k][j][:n] = getattr(ps, f"loading_{k}")
    data["pathset_fingerprint"] = (("t_over_R", "h_over_R"), fps, _attrs(
        "1", "catalogue fingerprint of the FE path set used (empty: none)"))
    data["gamma_max_hat"] = (("t_over_R", "h_over_R"), gmax, _attrs(
        "1", "largest gamma / (C10 R) the shell's FE paths serve"))
    data["mesh_even_arc_mm"] = (("t_over_R", "h_over_R"), length_mm(even, R), _attrs(
        "mm", "arc length from the apex meshed evenly (the mesh zone of the shell's paths)",
        comment="fitted to every point the shell's paths serve (up to gamma_max_hat, over "
                "all C10); solve_case of the same shell fits its mesh to its own gammas (its "
                "provenance: fit.even_arc_mm), so the two answers come from different meshes "
                "and can differ"))
    data.update(_checks(served, index, shells, C10s, R))
    data["pull_off_inverted"] = (DIMS, inverted, _attrs(
        "1", "pull-off point bridges or follows a contact-zone inversion (1 yes, 0 no, "
             "NaN: not evaluated)"))
    if study.outputs.relaxation_curves:
        data.update(_relaxation_curves(served, index, shells, C10s, R))
    if study.outputs.deformed_states:
        data.update(_deformed_states(served, index, shells, C10s, R))
    if study.outputs.loading_curves:
        L = ("t_over_R", "h_over_R", "loading_state")
        data["loading_delta_mm"] = (L, length_mm(load["delta"], R), _attrs(
            "mm", "rim displacement delta on loading without adhesion"))
        data["loading_a"] = (L, length_mm(load["a"], R), _attrs(
            "mm", "contact radius a on loading without adhesion"))
        c = C10s[:, None, None, None]
        data["loading_P"] = (("C10", *L), force_N(load["P"][None], c, R), _attrs(
            "N", "rim force P on loading without adhesion"))
        data["loading_U"] = (("C10", *L), energy_mJ(load["U"][None], c, R), _attrs(
            "mJ", "strain energy U on loading without adhesion"))
        if study.error_bars:
            err = np.full(shells + (n_load,), np.nan)
            for (t, h), (_, ps) in served.items():
                if (t, h) in coarser:
                    cps = coarser[t, h][1]
                    j = (index["t_over_R"][t], index["h_over_R"][h])
                    n = len(ps.loading_delta)
                    err[j][:n] = curve_error(ps.loading_delta, ps.loading_P,
                                             cps.loading_delta, cps.loading_P)
            data["loading_P_error"] = (("C10", *L), force_N(err[None], c, R), _attrs(
                "N", "discretisation error estimate of the loading P (NaN: beyond the "
                     "coarser mesh's loading)"))

    C10_attrs = _attrs("MPa", "neo-Hookean constant C10 (shear modulus / 2)")
    gamma_attrs = _attrs(GAMMA_UNITS, "work of adhesion gamma")
    coords = {
        "C10": ("C10", C10s, C10_attrs),
        "t_over_R": ("t_over_R", np.array(ax["t_over_R"]),
                     _attrs("1", "shell thickness over outer radius t/R")),
        "h_over_R": ("h_over_R", np.array(ax["h_over_R"]),
                     _attrs("1", "cap depth over outer radius h/R")),
        "gamma": ("gamma", gammas, gamma_attrs),
        "C10_MPa": ("C10", C10s, C10_attrs),
        "gamma_J_m2": ("gamma", gammas, gamma_attrs),
        "t_mm": ("t_over_R", np.array(ax["t_over_R"]) * R, _attrs("mm", "shell thickness t")),
        "h_mm": ("h_over_R", np.array(ax["h_over_R"]) * R, _attrs("mm", "cap depth h")),
        "R": ((), R, _attrs("mm", "outer radius of curvature R")),
    }
    # what labels a point or a curve is a coordinate, so that .sel and .plot(x=...) see it
    coords.update({k: data.pop(k) for k in CURVE_COORDS if k in data})
    sizes = {d: n for v in (*data.values(), *coords.values())
             for d, n in zip(v[0], np.shape(v[1]))}
    for dim, long_name in _INDEX_DIMS.items():
        if dim in sizes:
            coords[dim] = (dim, np.arange(sizes[dim], dtype=INDEX_DTYPE), _attrs("1", long_name))
    return xr.Dataset(data, coords=coords, attrs=_global_attrs(plan, history))


_INDEX_DIMS = {
    "point": "index along the equilibrium curve (increasing contact radius)",
    "loading_state": "index of the loading state (increasing delta)",
    "relaxation": "index of the relaxation path (increasing held contact radius)",
    "relaxation_state": "index along a relaxation path (delta decreasing from loading)",
    "profile": "index of the kept deformed state (loading, then relaxation)",
    "outer_node": "outer-surface node, from the axis to the rim",
    "inner_node": "inner-surface node, from the axis to the rim",
    "stress_map": "index of the kept von Mises map (end of loading, then relaxation)",
    "node": "finite-element node",
    "triangle": "plotting triangle (8 per quadratic element)",
    "vertex": "vertex of a triangle",
}


# what the solver checked per shell: stats key -> (variable, units, long_name, kind)
_CHECKS = {
    "delta_reached": ("loading_delta_reached", "mm", "deepest rim displacement the loading "
                      "reached (below delta_max: see loading_stopped_by)", "length"),
    "J_min": ("J_min", "1", "smallest pointwise volume ratio J over the loading states", "1"),
    "J_max": ("J_max", "1", "largest pointwise volume ratio J over the loading states", "1"),
    "detF_min": ("detF_min", "1", "smallest in-plane det F over the loading states", "1"),
    "distortion_min": ("distortion_min", "1", "smallest within-element det F ratio over "
                       "the loading states", "1"),
    "relaxation_J_min": ("relaxation_J_min", "1", "smallest pointwise J over the relaxation "
                         "paths (reported, not refused: crack tip)", "1"),
    "relaxation_J_max": ("relaxation_J_max", "1", "largest pointwise J over the relaxation "
                         "paths (reported, not refused: crack tip)", "1"),
    "inversion_delta": ("inversion_delta", "mm", "rim displacement where the contact zone's "
                        "centre first left the plane (NaN: never)", "length"),
    "inversion_a": ("inversion_a", "mm", "contact radius where the contact zone's centre "
                    "first left the plane (NaN: never)", "length"),
    "inverted_paths": ("inverted_paths", "1", "relaxation paths whose contact zone inverted "
                       "(left out of the energy method)", "1"),
}


def _checks(served, index, shells, C10s, R) -> dict:
    """Per shell: how far the loading got and why it stopped, the worst element quality,
    where the contact zone inverted; with C10, the largest gamma every pair reached."""
    values = {k: np.full(shells, np.nan) for k in _CHECKS}
    stopped = np.full(shells, "", dtype=object)
    G = np.full(shells, np.nan)
    for (t, h), (_, ps) in served.items():
        j = (index["t_over_R"][t], index["h_over_R"][h])
        for k in _CHECKS:
            v = ps.stats.get(k)
            values[k][j] = np.nan if v is None else float(v)
        stopped[j] = ps.stats.get("loading_stopped_by") or ""
        g = ps.stats.get("G_max_reached")
        G[j] = np.nan if g is None else float(g)
    S = ("t_over_R", "h_over_R")
    out = {}
    for k, (name, units, long_name, kind) in _CHECKS.items():
        v = length_mm(values[k], R) if kind == "length" else values[k]
        out[name] = (S, v, _attrs(units, long_name))
    out["loading_stopped_by"] = (S, stopped, _attrs(
        "1", "why the loading stopped before delta_max (empty: it reached delta_max)"))
    out["G_max_reached"] = (("C10", *S), G[None] * C10s[:, None, None] * R * 1e3, _attrs(
        GAMMA_UNITS, "largest gamma every pair of neighbouring relaxation paths reached"))
    return out


def _padded(shells, items, width):
    """(t, h, len, *width) NaN-padded array from {(j_t, j_h): list of arrays}."""
    n = max([len(v) for v in items.values()], default=0)
    out = np.full(shells + (n, *width), np.nan)
    for j, v in items.items():
        for k, x in enumerate(v):
            out[j + (k, *(slice(0, m) for m in np.shape(x)))] = x
    return out


def _relaxation_curves(served, index, shells, C10s, R) -> dict:
    """Every relaxation path of each shell (the raw material of Maugis' method)."""
    rel = {(index["t_over_R"][t], index["h_over_R"][h]): ps.relaxations
           for (t, h), (_, ps) in served.items()}
    width = (max([len(r.delta) for v in rel.values() for r in v], default=0),)
    delta = _padded(shells, {j: [r.delta for r in v] for j, v in rel.items()}, width)
    P = _padded(shells, {j: [r.P for r in v] for j, v in rel.items()}, width)
    U = _padded(shells, {j: [r.U for r in v] for j, v in rel.items()}, width)
    dP = _padded(shells, {j: [r.dP_ddelta for r in v] for j, v in rel.items()}, width)
    edge = _padded(shells, {j: [r.a_edge for r in v] for j, v in rel.items()}, width)
    slope = _padded(shells, {j: [r.da_ddelta for r in v] for j, v in rel.items()}, width)
    comply = _padded(shells, {j: [r.dA_dgamma for r in v] for j, v in rel.items()}, width)
    a = _padded(shells, {j: [r.a for r in v] for j, v in rel.items()}, ())
    used = _padded(shells, {j: [float(r.usable) for r in v]
                            for j, v in rel.items()}, ())
    c = C10s[:, None, None, None, None]
    S, K = ("t_over_R", "h_over_R", "relaxation"), ("t_over_R", "h_over_R", "relaxation",
                                                    "relaxation_state")
    return {
        "relaxation_a_mm": (S, length_mm(a, R), _attrs("mm", "held contact radius a of the path")),
        "relaxation_used": (S, used, _attrs(
            "1", "path used by the energy method (1), or left out because the centre lifts "
                 "or a free node touches (0)")),
        "relaxation_delta_mm": (K, length_mm(delta, R), _attrs(
            "mm", "rim displacement delta along the relaxation at fixed contact radius")),
        "relaxation_P": (("C10", *K), force_N(P[None], c, R), _attrs(
            "N", "rim force P along the relaxation at fixed contact radius")),
        "relaxation_U": (("C10", *K), energy_mJ(U[None], c, R), _attrs(
            "mJ", "strain energy U_E along the relaxation at fixed contact radius")),
        "relaxation_dP_ddelta": (("C10", *K), force_N(dP[None], c, R) / R, _attrs(
            "N/mm", "stiffness dP/d(delta) along the relaxation at fixed contact radius")),
        "relaxation_edge_mm": (K, length_mm(edge, R), _attrs(
            "mm", "deformed radius of the held edge along the relaxation (the covered radius; "
                  "frictionless edges slide, no_slip ones stay at relaxation_a_mm)")),
        "relaxation_dedge_ddelta": (K, slope, _attrs(
            "1", "slope d(relaxation_edge_mm)/d(relaxation_delta_mm) along the relaxation")),
        "relaxation_dA_dgamma": (("C10", *K), comply[None] * R / c, _attrs(
            "mm^3/N", "compliance dA/dgamma of the area the held set covers, at fixed delta, "
                      "gamma in N/mm (x 1e-3: mm^2 per J/m^2): the adhesive edge force's "
                      "second order (0 where the edge cannot slide)")),
    }


def _deformed_states(served, index, shells, C10s, R) -> dict:
    """Deformed profiles and von Mises maps kept by each shell's FE paths."""
    from shell_adhesion.solver.postprocess import Profile, StressMap
    prof, maps = {}, {}
    for (t, h), (_, ps) in served.items():
        j = (index["t_over_R"][t], index["h_over_R"][h])
        prof[j] = [v for v in ps.views if isinstance(v, Profile)]
        maps[j] = [v for v in ps.views if isinstance(v, StressMap)]
    out = {}
    dims = ("t_over_R", "h_over_R")
    for kind, items, dim in (("profile", prof, "profile"), ("map", maps, "stress_map")):
        stage = np.full(shells + (max([len(v) for v in items.values()], default=0),), "",
                        dtype=object)
        for j, v in items.items():
            stage[j][:len(v)] = [x.stage for x in v]
        scal = {k: _padded(shells, {j: [getattr(x, k) for x in v] for j, v in items.items()}, ())
                for k in ("a", "delta", "P")}
        what = "deformed state" if kind == "profile" else "von Mises map"
        out[f"{kind}_stage"] = ((*dims, dim), stage, _attrs(
            "1", f"stage of the {what}: loading, or relaxation at its fixed contact radius"))
        out[f"{kind}_a"] = ((*dims, dim), length_mm(scal["a"], R), _attrs(
            "mm", f"contact radius a of the {what}"))
        out[f"{kind}_delta"] = ((*dims, dim), length_mm(scal["delta"], R), _attrs(
            "mm", f"rim displacement delta of the {what}"))
        out[f"{kind}_P"] = (("C10", *dims, dim), force_N(scal["P"][None], C10s[:, None, None, None], R),
                            _attrs("N", f"rim force P of the {what}"))
    for side in ("outer", "inner"):
        width = (max([getattr(x, side).shape[1] for v in prof.values() for x in v], default=0),)
        for i, c in enumerate("rz"):
            arr = _padded(shells, {j: [getattr(x, side)[i] for x in v] for j, v in prof.items()},
                          width)
            out[f"profile_{side}_{c}"] = ((*dims, "profile", f"{side}_node"), length_mm(arr, R),
                                          _attrs("mm", f"deformed {c} of the {side} surface"
                                                       + (" (plane at z = 0)" if c == "z" else "")))
    width = (max([x.nodes.shape[1] for v in maps.values() for x in v], default=0),)
    M = (*dims, "stress_map", "node")
    for i, c in enumerate("rz"):
        arr = _padded(shells, {j: [x.nodes[i] for x in v] for j, v in maps.items()}, width)
        out[f"map_{c}"] = (M, length_mm(arr, R), _attrs("mm", f"deformed {c} of every node"))
    vm = _padded(shells, {j: [x.von_mises for x in v] for j, v in maps.items()}, width)
    out["map_von_mises"] = (("C10", *M), vm[None] * C10s[:, None, None, None, None], _attrs(
        "MPa", "von Mises stress at the nodes (mean over the elements holding each)"))
    ntri = max([v[0].triangles.shape[0] for v in maps.values() if v], default=0)
    tri = np.full(shells + (ntri, 3), -1, dtype=np.int32)
    for j, v in maps.items():
        if v:
            tri[j][:len(v[0].triangles)] = v[0].triangles
    out["map_triangles"] = ((*dims, "triangle", "vertex"), tri, _attrs(
        "1", "node indices of the plotting triangles (-1: padding)"))
    return out


def _global_attrs(plan: Plan, history: str) -> dict:
    study = plan.study
    s = plan.settings
    return dict(
        title=study.description or f"shell-adhesion study {study.name}",
        history=history or f"{datetime.now(timezone.utc).isoformat(timespec='seconds')} "
                           f"shell-adhesion {solver.__version__}",
        source=f"shell-adhesion {solver.__version__}: axisymmetric Q2/Q1 finite elements of an "
               "incompressible neo-Hookean spherical-cap shell on a rigid plane, Maugis' "
               "energy method",
        Conventions="CF-1.8",
        references="Adherence of a hyperelastic shell on a rigid planar substrate",
        comment="Full cube over the union of the study's values; only the requested points "
                "(base, sweep lines, grid) are evaluated, the others are NaN with status "
                "'not requested'. P > 0 compression, delta > 0 approach.",
        **study_attrs(study.as_dict()),
        study_file=study.source, study_sha256=study.sha256,
        gamma_max_ladder=", ".join(str(m) for m in request.LADDER) + " x 10^k",
        solver_version=solver.__version__, solver_source_sha256=solver_source_sha256(),
        **{f"solver_{k}": int(v) if isinstance(v, bool) else v for k, v in asdict(s).items()},
        relaxation_G_SAFETY=case.G_SAFETY,
    )


def write(ds: xr.Dataset, path) -> None:
    """Write the cube to `path` atomically (netCDF4, compressed floats).

    CF: a coordinate variable has no _FillValue, nor does a coordinate that is never
    missing; the NaN-padded curve coordinates keep theirs."""
    enc = {v: {"zlib": True, "complevel": 4} for v in ds.variables
           if ds[v].dtype.kind == "f" and ds[v].ndim > 0 and ds[v].size > 0}
    for c in ds.coords:
        if ds[c].dtype.kind == "f" and (c in ds.dims or not ds[c].isnull().any()):
            enc.setdefault(c, {})["_FillValue"] = None
    write_atomic(ds, path, enc)


def content_sha256(ds: xr.Dataset) -> str:
    """Digest of what the cube holds: every variable's name, dimensions, type, attributes
    and values, and the global attributes but `history` (when and how it was written)."""
    h = hashlib.sha256()
    for name in sorted(ds.variables):
        v = ds.variables[name]
        h.update(repr((name, v.dims, str(v.dtype), sorted(v.attrs.items()))).encode())
        values = np.ascontiguousarray(v.values)
        h.update(repr(values.tolist()).encode() if values.dtype.kind == "O"
                 else values.tobytes())
    h.update(repr(sorted((k, v) for k, v in ds.attrs.items() if k != "history")).encode())
    return h.hexdigest()


def inputs_sha256(plan: Plan, entries) -> str:
    """Digest of all a cube is built from, known before building it: the validated study
    and settings, the stored path sets serving its shells (catalogue Entries in plan
    order: fingerprints and file digests), this package's sources and the versions of
    the numerical libraries.  Equal digests build cubes of equal content_sha256."""
    import scipy
    root = Path(solver.__file__).parent.parent
    h = hashlib.sha256()
    h.update(repr((plan.study, plan.settings)).encode())
    for e in entries:
        h.update(f"{e.fingerprint} {e.sha256}\n".encode())
    for p in sorted(root.rglob("*.py")):
        h.update(str(p.relative_to(root)).encode() + b"\0" + p.read_bytes() + b"\0")
    h.update(repr((solver.__version__, np.__version__, scipy.__version__,
                   xr.__version__)).encode())
    return h.hexdigest()


def summary_counts(ds: xr.Dataset) -> dict:
    """Number of points per status."""
    values, counts = np.unique(ds["status"].values.astype(str), return_counts=True)
    return {s: int(counts[values == s].sum()) for s in STATUS}
