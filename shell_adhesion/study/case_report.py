"""The result of one shell in units (study.case.CaseResult), as JSON-able data and as an
xarray Dataset: lengths mm, forces N, energies mJ, C10 MPa, gamma J/m^2.

Both renderings read the same dimensional values (`_values`); the Dataset uses the names
of the study's cube (P_star, a_eq_mm, loading_P, relaxation_delta_mm, ...), with the curves'
abscissas as coordinates so that ``ds.P_eq.sel(gamma=30).plot(x="a_eq_mm")`` works.
"""
import numpy as np
import xarray as xr

from shell_adhesion.cube import CURVES, PULL_OFF     # the cube's names, units and long names
from shell_adhesion import theory
from shell_adhesion.solver.error_bars import (assumed_order, coarsest_usable, curve_error,
                                               error_bar, observed_order,
                                               refines_through_thickness, rule)
from shell_adhesion.solver.scaling import energy_mJ, force_N, length_mm

from .a0_note import a0_note
from .case_input import cavity_kPa, material_MPa

def _attrs(units, long_name):
    return dict(units=units, long_name=long_name)


def _values(result):
    """Dimensional arrays of a CaseResult: (loading, relaxations, adhesion).

    loading: dict of arrays; relaxations: list of dicts; adhesion: list of (gamma,
    pull-off values dict, equilibrium curve dict).
    """
    inp, ps = result.input, result.pathset
    R, C10 = inp.R_mm, inp.C10_MPa
    L = lambda x: length_mm(np.asarray(x, dtype=float), R)
    F = lambda x: force_N(np.asarray(x, dtype=float), C10, R)
    E = lambda x: energy_mJ(np.asarray(x, dtype=float), C10, R)
    V = lambda x: np.asarray(x, dtype=float) * R ** 3
    kPa = lambda x: np.asarray(x, dtype=float) * C10 * 1e3
    loading = dict(delta=L(ps.loading_delta), P=F(ps.loading_P), a=L(ps.loading_a),
                   U=E(ps.loading_U), V=V(ps.loading_V), p=kPa(ps.loading_p))
    cps = result.coarser
    if cps is not None:
        loading["P_error"] = curve_error(loading["delta"], loading["P"],
                                         L(cps.loading_delta), F(cps.loading_P))
    relaxations = [dict(a=float(L(r.a)), delta=L(r.delta), P=F(r.P), U=E(r.U),
                        dP=F(r.dP_ddelta) / R, V=V(r.V), p=kPa(r.p),
                        ended_by=r.ended_by, centre_lifts=bool(r.centre_lifts),
                        penetration=bool(r.penetration), usable=r.usable)
                   for r in ps.relaxations] if inp.gamma_J_m2 else []
    adhesion = []
    answered = {g: (eq, po) for g, eq, po in result.adhesion}
    coarser = dict(zip(answered, result.coarser_pull_off or ()))
    coarsest = (dict(zip(answered, result.coarsest_pull_off or ()))
                if coarsest_usable(result.input.t_mm / result.input.R_mm, result.input.mesh)
                else {})
    refused = dict(result.refused)
    conv = dict(force=F, length=L)
    observable = order_observable(result)
    order = assumed_order(inp.t_mm / R, inp.mesh)      # of a bar from two meshes

    def dimensional(po, g):
        if po is None:
            return None
        v = {k: float(conv[kind](getattr(po, k))) for k, (_, _, kind) in PULL_OFF.items()}
        v["eta"] = theory.eta_of(v["P_star"], R, inp.t_mm, C10, g, inp.material)
        return v

    for g in inp.gamma_J_m2:
        if g in refused:
            values = {k: np.nan for k in (*PULL_OFF, "eta")}
            values.update(status="out of range", reason=refused[g])
            empty = np.zeros(0)
            curve = dict(a=empty, delta=empty, P=empty, stable_fixed_load=empty.astype(bool),
                         stable_fixed_grips=empty.astype(bool))
        else:
            eq, po = answered[g]
            values = dict(dimensional(po, g), status="ok", reason=po.note,
                          edge_growth=po.edge_growth)
            curve = dict(a=L(eq.a), delta=L(eq.delta), P=F(eq.P),
                         stable_fixed_load=np.asarray(eq.stable_fixed_load, dtype=bool),
                         stable_fixed_grips=np.asarray(eq.stable_fixed_grips, dtype=bool))
        if cps is not None:
            c2, c3 = dimensional(coarser.get(g), g), dimensional(coarsest.get(g), g)
            for k in (*PULL_OFF, "eta"):
                x2 = np.nan if c2 is None else c2[k]
                x3 = None if c3 is None else c3[k]
                values[f"{k}_error"] = float(error_bar(values[k], x2, x3, observable, order))
                values[f"{k}_order"] = (float(observed_order(values[k], x2, x3, observable))
                                        if x3 is not None else np.nan)
                values[f"{k}_rule"] = rule(values[k], x2, x3, observable, order)
        values["jkr_P_star"] = theory.jkr_P_star_N(R, g)
        adhesion.append((g, values, curve))
    return loading, relaxations, adhesion


def order_observable(result) -> bool:
    """Whether the answer's mesh and its two coarser companions form a family whose
    observed order is usable: each step adds layers through the thickness
    (`refines_through_thickness`) and all three relax contact fronts ending on the same
    node type (corner or midside, solver.case.relaxation_starts; unknown counts as the
    same)."""
    inp = result.input
    families = {ps.stats.get("relaxation_family")
                for ps in (result.pathset, result.coarser, result.coarsest) if ps is not None}
    return (refines_through_thickness(inp.t_mm / inp.R_mm, inp.mesh)
            and len(families - {None}) <= 1)


# -- JSON ------------------------------------------------------------------------------

def _num(v, digits=10):
    """A JSON-safe number: None where the value is undefined (NaN)."""
    v = float(v)
    return None if not np.isfinite(v) else float(f"{v:.{digits}g}")


def _list(x, digits=10):
    return [_num(v, digits) for v in np.asarray(x, dtype=float)]


def as_dict(result, curves: bool = False) -> dict:
    """Plain JSON-able data: input, material (model, coefficients in MPa, D1 in 1/MPa),
    pull_off (one entry per gamma: values with units in their names, error bars, status)
    and provenance; with `curves` also loading, and with gamma relaxation and equilibrium
    (the curves, a few thousand numbers)."""

    loading, relaxations, adhesion = _values(result)
    out = {"input": result.input.as_dict(),
           "material": material_MPa(result.input.material, result.input.C10_MPa)}
    if curves:
        out.update(_curves_dict(result, loading, relaxations, adhesion))
    if adhesion:
        out["pull_off"] = [_pull_off_dict(g, v) for g, v, _ in adhesion]
        missing = (result.provenance.get("error_bars") or {}).get("not_given", {})
        for po, (_, _, curve) in zip(out["pull_off"], adhesion):
            if f"{po['gamma_J_m2']:g}" in missing:     # the error bar says why it is not there
                po["error_note"] = missing[f"{po['gamma_J_m2']:g}"]
            if po["status"] == "ok" and po["a0_mm"] is None and len(curve["a"]):
                po["a0_note"] = a0_note(result.input, result.provenance, float(curve["a"][-1]),
                                        float(curve["P"][-1]))
    out["provenance"] = result.provenance
    return out


def _curves_dict(result, loading, relaxations, adhesion) -> dict:
    """The curves in units: loading, and with gamma relaxation and equilibrium."""
    out = {"loading": {"delta_mm": _list(loading["delta"]), "P_N": _list(loading["P"]),
                       "a_mm": _list(loading["a"]), "U_E_mJ": _list(loading["U"])}}
    closed = result.input.cavity.closed
    if closed:   # the enclosed volume and the gauge pressure of a closed cavity
        out["loading"].update(V_mm3=_list(loading["V"]), p_kPa=_list(loading["p"]))
    if "P_error" in loading:
        out["loading"]["P_N_error"] = _list(loading["P_error"])
    if adhesion:
        out["relaxation"] = [
            {"a_mm": _num(r["a"]), "delta1_mm": _num(r["delta"][0]), "P1_N": _num(r["P"][0]),
             "delta_mm": _list(r["delta"]), "P_N": _list(r["P"]), "U_E_mJ": _list(r["U"]),
             "dP_ddelta_N_mm": _list(r["dP"]), "ended_by": r["ended_by"], "centre_lifts": r["centre_lifts"],
             "penetration": r["penetration"],
             **({"V_mm3": _list(r["V"]), "p_kPa": _list(r["p"])} if closed else {})}
            for r in relaxations]
        out["equilibrium"] = [
            {"gamma_J_m2": g, "a_mm": _list(c["a"]), "P_N": _list(c["P"]),
             "delta_mm": _list(c["delta"]),
             "stable_fixed_load": [bool(v) for v in c["stable_fixed_load"]],
             "stable_fixed_grips": [bool(v) for v in c["stable_fixed_grips"]]}
            for g, v, c in adhesion if v["status"] == "ok"]
    return out


# JSON name of each pull-off value: (group or None, name)
_JSON_NAMES = {"P_star": ("fixed_load", "P_N"), "delta_star": ("fixed_load", "delta_mm"),
               "a_star": ("fixed_load", "a_mm"), "P_dagger": ("fixed_grips", "P_N"),
               "delta_dagger": ("fixed_grips", "delta_mm"), "a_dagger": ("fixed_grips", "a_mm"),
               "a0": (None, "a0_mm"), "eta": (None, "eta")}


def _pull_off_dict(g, v) -> dict:
    """One gamma's pull-off: its status ("ok", or "out of range" with the reason and no
    values); with error bars, "<name>_error" beside each "<name>", "<name>_order", the
    order observed on three meshes (None: order 1 assumed; solver.error_bars), and
    "<name>_rule", the rule in words (`solver.error_bars.rule`)."""
    out = {"gamma_J_m2": g, "status": v["status"]}
    if v["reason"]:         # not answered, or the fixed grips not (PullOff.note)
        out["reason"] = v["reason"]
    if v["status"] != "ok":
        return out
    out.update(fixed_load={}, fixed_grips={})
    for k, (group, name) in _JSON_NAMES.items():
        where = out[group] if group else out
        where[name] = _num(v[k])
        for extra in ("error", "order", "rule"):
            if f"{k}_{extra}" in v:
                x = v[f"{k}_{extra}"]
                where[f"{name}_{extra}"] = x if extra == "rule" else _num(x)
    # frictionless: how far the adhesive edge force grows the covered area at a*
    # (PullOff.edge_growth; the energy method takes the force to second order)
    out["fixed_load"]["edge_growth"] = _num(v.get("edge_growth", np.nan))
    out["jkr_P_star_N"] = _num(v["jkr_P_star"])
    return out


# -- Dataset ---------------------------------------------------------------------------

def _padded(arrays):
    """(len(arrays), longest) array, each row NaN-padded."""
    width = max([len(a) for a in arrays], default=0)
    out = np.full((len(arrays), width), np.nan)
    for i, a in enumerate(arrays):
        out[i, :len(a)] = a
    return out


def as_dataset(result) -> xr.Dataset:
    """Named dimensions gamma, loading_state, relaxation, relaxation_state and point;
    `units` and `long_name` on every variable and coordinate."""
    inp, prov = result.input, result.provenance
    loading, relaxations, adhesion = _values(result)
    n_load = len(loading["delta"])
    gammas = np.array([g for g, _, _ in adhesion], dtype=float)
    curves = [c for _, _, c in adhesion]
    data = {
        "loading_P": ("loading_state", loading["P"],
                      _attrs("N", "rim force P on loading without adhesion")),
        "loading_a": ("loading_state", loading["a"],
                      _attrs("mm", "contact radius a on loading without adhesion")),
        "loading_U": ("loading_state", loading["U"],
                      _attrs("mJ", "strain energy U on loading without adhesion")),
    }
    if "P_error" in loading:
        data["loading_P_error"] = ("loading_state", loading["P_error"], _attrs(
            "N", "discretisation error estimate of the loading P (NaN: beyond the coarser "
                 "mesh's loading)"))
    coords = {
        "R": ((), inp.R_mm, _attrs("mm", "outer radius of curvature R")),
        "t_mm": ((), inp.t_mm, _attrs("mm", "shell thickness t")),
        "h_mm": ((), inp.h_mm, _attrs("mm", "cap depth h")),
        "C10_MPa": ((), inp.C10_MPa, _attrs("MPa", "material constant C10 (the scaling "
                                                   "modulus; neo-Hookean shear modulus / 2)")),
        **_material_coords(inp.material, inp.C10_MPa),
        "loading_state": ("loading_state", np.arange(n_load),
                          _attrs("1", "index of the loading state (increasing delta)")),
        "loading_delta_mm": ("loading_state", loading["delta"],
                          _attrs("mm", "rim displacement delta on loading without adhesion")),
    }
    closed = inp.cavity.closed
    if closed:      # a closed cavity's volume and gauge pressure (study.case_input.cavity_kPa)
        data["loading_V"] = ("loading_state", loading["V"], _attrs(
            "mm3", "cavity volume V (inner surface and lid) on loading"))
        data["loading_p"] = ("loading_state", loading["p"], _attrs(
            "kPa", "cavity gauge pressure p on loading (> 0 inflates)"))
    if adhesion:
        K = ("relaxation", "relaxation_state")
        if closed:
            data["relaxation_V"] = (K, _padded([r["V"] for r in relaxations]), _attrs(
                "mm3", "cavity volume V along the relaxation at fixed contact radius"))
            data["relaxation_p"] = (K, _padded([r["p"] for r in relaxations]), _attrs(
                "kPa", "cavity gauge pressure p along the relaxation at fixed contact radius"))
        data["relaxation_P"] = (K, _padded([r["P"] for r in relaxations]), _attrs(
            "N", "rim force P along the relaxation at fixed contact radius"))
        data["relaxation_U"] = (K, _padded([r["U"] for r in relaxations]), _attrs(
            "mJ", "strain energy U_E along the relaxation at fixed contact radius"))
        data["relaxation_dP_ddelta"] = (K, _padded([r["dP"] for r in relaxations]), _attrs(
            "N/mm", "stiffness dP/d(delta) along the relaxation at fixed contact radius"))
        data["relaxation_used"] = ("relaxation", np.array(
            [int(r["usable"]) for r in relaxations], dtype=np.int8), _attrs(
            "1", "path used by the energy method (1), or left out because the centre lifts "
                 "or a free node touches (0)"))
        coords["relaxation_delta_mm"] = (K, _padded([r["delta"] for r in relaxations]), _attrs(
            "mm", "rim displacement delta along the relaxation at fixed contact radius"))
        coords["relaxation_a_mm"] = ("relaxation", np.array([r["a"] for r in relaxations]),
                                  _attrs("mm", "held contact radius a of the path"))
        coords["relaxation"] = ("relaxation", np.arange(len(relaxations)), _attrs(
            "1", "index of the relaxation path (increasing held contact radius)"))
        coords["relaxation_state"] = (
            "relaxation_state", np.arange(data["relaxation_P"][1].shape[1]),
            _attrs("1", "index along a relaxation path (delta decreasing from loading)"))
        for k, (units, long_name, _) in PULL_OFF.items():
            data[k] = ("gamma", np.array([v[k] for _, v, _ in adhesion]),
                       _attrs(units, long_name))
        data["eta"] = ("gamma", np.array([v["eta"] for _, v, _ in adhesion]), _attrs(
            "1", "eta of eq. 3: |P*| / [gamma^4 R^4 (1 - nu^2) / (E t^2)]^(1/3)"))
        for k in (*PULL_OFF, "eta"):
            if f"{k}_error" in adhesion[0][1]:
                units = PULL_OFF[k][0] if k in PULL_OFF else "1"
                data[f"{k}_error"] = ("gamma", np.array([v[f"{k}_error"] for _, v, _ in adhesion]),
                                      _attrs(units, f"discretisation error estimate of {k}"))
                data[f"{k}_order"] = ("gamma", np.array([v[f"{k}_order"] for _, v, _ in adhesion]),
                                      _attrs("1", f"order of convergence of {k} observed on "
                                                  "three meshes (NaN: order 1 assumed)"))
                data[f"{k}_rule"] = ("gamma", np.array([v[f"{k}_rule"] for _, v, _ in adhesion],
                                                       dtype=object),
                                     _attrs("1", f"the rule of {k}'s error estimate "
                                                 "(solver.error_bars.rule)"))
        data["status"] = ("gamma", np.array([v["status"] for _, v, _ in adhesion], dtype=object),
                          _attrs("1", "evaluation status of the gamma (ok or out of range)"))
        data["reason"] = ("gamma", np.array([v["reason"] for _, v, _ in adhesion], dtype=object),
                          _attrs("1", "why the gamma is not answered, or why its fixed-grips "
                                      "values are not (empty: all given)"))
        data["jkr_P_star"] = ("gamma", np.array([v["jkr_P_star"] for _, v, _ in adhesion]),
                              _attrs("N", "JKR pull-off force of a solid sphere of radius R"))
        E = ("gamma", "point")
        for k, (units, long_name) in CURVES.items():
            values = _padded([c[k.removesuffix("_mm").removesuffix("_eq")].astype(float)
                              for c in curves])
            (coords if k == "a_eq_mm" else data)[k] = (E, values, _attrs(units, long_name))
        coords["point"] = ("point", np.arange(data["P_eq"][1].shape[1]), _attrs(
            "1", "index along the equilibrium curve (increasing contact radius)"))
    coords["gamma"] = ("gamma", gammas, _attrs("J/m^2", "work of adhesion gamma"))
    coords["gamma_J_m2"] = ("gamma", gammas, _attrs("J/m^2", "work of adhesion gamma"))
    attrs = dict(
        title=f"shell-adhesion case: R = {inp.R_mm:g} mm, t = {inp.t_mm:g} mm, "
              f"h = {inp.h_mm:g} mm, {inp.material.coefficients(inp.C10_MPa)}",
        Conventions="CF-1.8",
        source=f"shell-adhesion {prov.get('version', '')}: axisymmetric finite elements of a "
               f"hyperelastic ({inp.material.model}) spherical-cap shell on a rigid plane, Maugis' "
               "energy method",
        material_model=inp.material.model,
        comment="P > 0 compression, delta > 0 approach; curves NaN-padded",
        interface=inp.interface, mesh=inp.mesh,
        delta_reached_mm=float(loading["delta"][-1]),
        dofs=prov.get("dofs", -1), newton_iterations=prov.get("newton_iterations", -1),
        wall_s=prov.get("wall_s", float("nan")),
        relaxation_gamma_max_over_C10R=prov.get("relaxation_gamma_max_over_C10R",
                                                float("nan")))
    if inp.delta_max_mm is not None:
        attrs["delta_max_mm"] = inp.delta_max_mm
    if closed:
        attrs.update({f"cavity_{k}": v for k, v in
                      cavity_kPa(inp.cavity, inp.C10_MPa).items() if v is not None},
                     cavity_apex_uz_mm=prov["cavity_touch"]["apex_uz_mm"],
                     comment=attrs["comment"] + "; P is the force on rim and lid, delta from "
                     "the first touch of the pressurised shell")
    return xr.Dataset(data, coords=coords, attrs=attrs)


def _material_coords(material, C10_MPa) -> dict:
    """Scalar coordinates of the coefficients the material uses besides C10 (MPa, Jm, D1)."""
    out = {}
    for model, ratio, name, long_name in (
            ("mooney_rivlin", "C01_over_C10", "C01", "Mooney-Rivlin constant C01"),
            ("yeoh", "C20_over_C10", "C20", "Yeoh constant C20"),
            ("yeoh", "C30_over_C10", "C30", "Yeoh constant C30")):
        if material.model == model:
            out[f"{name}_MPa"] = ((), getattr(material, ratio) * C10_MPa, _attrs("MPa", long_name))
    if material.Jm is not None:
        out["Jm"] = ((), material.Jm, _attrs("1", "Gent limit Jm of I1bar - 3"))
    if material.compressible:
        out["D1_per_MPa"] = ((), material.D1_times_C10 / C10_MPa, _attrs(
            "MPa-1", "compressibility D1, U = (J - 1)^2 / D1"))
    return out
