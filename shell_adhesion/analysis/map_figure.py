"""Figure of a pull-off map: P*/(C10 R^2) over t/R and h/R at one gamma/(C10 R), beside
the map's stated relative error (interpolation and FE in quadrature), grid points marked."""
import math

import numpy as np

SAMPLES = 81        # per axis
TICKS = (0.02, 0.05, 0.1, 0.2, 0.4, 1.0)


def draw_map(pm, gamma_hat, path):
    """Write the figure of map `pm` (analysis.pull_off_map.PullOffMap) at gamma_hat."""
    from matplotlib.figure import Figure
    from matplotlib.ticker import FixedLocator, FormatStrFormatter, NullFormatter
    from .pull_off_map import MapError

    (tlo, thi), (hlo, hhi) = pm.bounds["t_over_R"], pm.bounds["h_over_R"]
    t = np.exp(np.linspace(math.log(tlo), math.log(thi), SAMPLES))
    h = np.linspace(hlo, hhi, SAMPLES)
    P = np.full((SAMPLES, SAMPLES), np.nan)
    err = np.full((SAMPLES, SAMPLES), np.nan)
    for j, hj in enumerate(h):
        for i, ti in enumerate(t):
            try:
                ans = pm.predict(ti, hj, gamma_hat)["P_star"]
            except MapError:
                continue
            P[j, i], err[j, i] = ans.value, 100 * ans.error / abs(ans.value)
    fig = Figure(figsize=(10, 4), layout="constrained")
    axes = fig.subplots(1, 2)
    panels = ((P, "viridis", r"$P^*/(C_{10}R^2)$"), (err, "magma_r", "stated error of $P^*$ [%]"))
    for ax, (z, cmap, label) in zip(axes, panels):
        im = ax.pcolormesh(t, h, z, cmap=cmap, shading="auto")
        fig.colorbar(im, ax=ax, label=label)
        if z is err:
            ax.contour(t, h, z, levels=[2.0], colors="w", linewidths=1.2)
        tt, hh = np.meshgrid(pm.ds["t_over_R"].values, pm.ds["h_over_R"].values)
        ax.plot(tt.ravel(), hh.ravel(), "k.", ms=4)
        ax.set(xscale="log", xlabel="t/R", ylabel="h/R")
        ax.xaxis.set_major_locator(FixedLocator([v for v in TICKS if tlo <= v <= thi]))
        ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
        ax.xaxis.set_minor_formatter(NullFormatter())
    axes[0].set_title(fr"$P^*$ at $\gamma/(C_{{10}}R)$ = {gamma_hat:g} "
                      f"({pm.ds.attrs.get('mesh', '')} mesh)")
    axes[1].set_title("its error bar (white: 2 %); dots: FE shells")
    fig.savefig(path, dpi=120)
