#!/usr/bin/python3
"""Builds the comparison report from penumbra-bench-compare's results.json alone (and, where
targets/web/three_peers.mjs wrote DIR/three_peers.md, appends its three.js tables).

    compare_report.py DIR [--mae-thresholds 0.1,0.15,0.2] [--metric M]   writes DIR/report.md, DIR/figures/*.png
    compare_report.py DIR --check                  exits 1 unless report, figures and finite numbers are there

Every conclusion in the report is computed here from the raw numbers: the Pareto fronts, the
equal-time table, the light-size tables, the per-scene and per-mesh tables and the excess flicker.
The conclusions use the shaded image's error (`shaded`: the `irradiance` reference's error, each pixel
weighed by the unoccluded irradiance it receives, so a face that gets almost no light counts for almost
nothing, as in the image a user sees) unless --metric says otherwise; the other references follow, named
for what they are (`irradiance`: an engine multiplies the visibility into its own unoccluded area-light
shading, so what it needs is the light weighed by the irradiance it sends; `oriented`, the visibility of
the part of the light above the receiver's tangent plane). Figures use Debian's matplotlib (python3-matplotlib), without a display (Agg backend).
"""
import argparse
import json
import math
import os
import sys
from collections import defaultdict

COST = "gpu_ms"  # the cost of a frame: median over the timed runs of the summed timer queries of every pass
REFERENCE = "PCSS 16/16"  # ratios are given against this setting at the same scene and light size
FALLBACK_REFERENCE = "OT nbuffer 16/512"  # when the run has no PCSS 16/16 (and says so)
EQUAL_TIME_BUDGETS = ["PCSS 16/16", "PCSS 32/64", "SMRT 8/16", "SMRT 4/8 TAA8"]
DEFAULT_SETTING = "OT nbuffer 16/512"  # Config{}: the default occlusion-texture configuration
KEY_SETTINGS = [DEFAULT_SETTING, "PCSS 16/16", "PCSS 32/64", "SMRT 7/8", "SMRT 8/16", "SMRT 4/8 TAA8"]  # the per-scene and per-mesh tables
FAMILY_NAMES = {"occlusion": "occlusion textures", "paper": "occlusion textures, the paper's model", "shadowmap": "hard shadow map", "pcf": "PCF", "pcss": "PCSS", "pcss-depth-bias-only": "PCSS with the depth bias only (no normal offset, no receiver-plane bias)", "erosion": "erosion", "evsm": "EVSM", "smrt": "shadow-map ray tracing (SMRT, one frame)", "smrt-temporal": "SMRT accumulated over N frames (time: one frame)", "oim": "occlusion interval maps", "compute-prefilter": "occlusion textures, compute prefilter", "chained-fusion": "occlusion textures, chained fusion (the default before extent)", "clustered-fusion": "occlusion textures, clustered fusion (crowds and foliage)", "area-weighted": "occlusion textures, the light weighed by area (the default before the irradiance window)"}
LIGHT_TITLES = {"rect": "the rectangle light", "sun": "the sun"}


def family_name(family):
    return FAMILY_NAMES.get(family, family)


def fmt_ms(ms):
    return f"{ms:.1f}" if ms >= 10 else f"{ms:.2f}"


def fmt_scale(scale):
    return f"x{scale:g}"


# The reference the conclusions use (--metric, default `shaded`: the shaded image's error); the others are
# shown beside it, in this order, each under the name that says what it measures.
METRICS = {
    "shaded": "the error against irradiance weighed by the unoccluded irradiance each pixel receives: the "
              "error of the shaded image in linear light, relative to the mean unoccluded irradiance over the same "
              "pixels (a face that "
              "gets almost no light weighs almost nothing)",
    "irradiance": "irradiance relative to the unoccluded irradiance from the part of the light above the receiver's "
                  "tangent plane (the shaded image's reference)",
    "oriented": "visibility of the part of the light above the receiver's tangent plane (fair)",
    "visibility": "visibility of the whole light (rays behind the receiver's tangent plane count as blocked: "
                  "unfair to a model that clips to the tangent plane, which the default does)",
}
METRIC_NAMES = {"shaded": "shaded image", "irradiance": "irradiance", "oriented": "oriented (fair)",
                "visibility": "whole-light visibility"}
METRIC = "shaded"


def metric_name(metric=None):
    return METRIC_NAMES[metric or METRIC]


def quality(m, metric=None):
    metric = metric or METRIC
    return m["quality"] if metric == "visibility" else m["quality"][metric]


def pen(m, metric=None):
    """Penumbra MAE against the chosen reference."""
    return quality(m, metric)["penumbra"]["mae"]


def fair_text(m):
    """The penumbra MAE against the two references the conclusions do not use."""
    return " / ".join(f"{pen(m, k):.3f}" for k in METRICS if k != METRIC)


def other_metrics():
    return " / ".join(metric_name(k) for k in METRICS if k != METRIC)


def bias(m):
    """Mean signed penumbra error against the chosen reference (older results: only whole-light visibility)."""
    q = quality(m)
    return q["penumbra_bias"] if "penumbra_bias" in q else m["quality"]["penumbra_bias"]


def has_bias(measurements):
    return all("penumbra_bias" in quality(m) for m in measurements)


def load(directory):
    with open(os.path.join(directory, "results.json")) as f:
        return json.load(f)


def light_of(m):
    """The light a measurement ran under; results.json from before --lights has only the rectangle."""
    return m.get("light", "rect")


def lights_of(results):
    """The lights of the run that have measurements, in the order of --lights."""
    order = results["meta"].get("lights", ["rect"])
    present = {light_of(m) for m in results["measurements"]}
    return [l for l in order if l in present] or ["rect"]


def suffix_of(light):
    """The rectangle's figures keep their names; the sun's end in _sun."""
    return "" if light == "rect" else f"_{light}"


def for_light(results, light):
    """results with only the measurements and flicker runs under `light`."""
    out = dict(results)
    out["measurements"] = [m for m in results["measurements"] if light_of(m) == light]
    out["flicker"] = [f for f in results["flicker"] if light_of(f) == light]
    return out


# ---- the computed conclusions ------------------------------------------------------------------

def by_cell(measurements):
    """(scene, light_scale) -> {label: measurement}"""
    cells = defaultdict(dict)
    for m in measurements:
        cells[(m["scene"], m["light_scale"])][m["label"]] = m
    return cells


def pareto_front(points):
    """Measurements not beaten on both cost and penumbra MAE, cheapest first."""
    front, best = [], math.inf
    for m in sorted(points, key=lambda m: (m[COST], pen(m))):
        if pen(m) < best:
            front.append(m)
            best = pen(m)
    return front


def reference_label(measurements):
    labels = {m["label"] for m in measurements}
    if REFERENCE in labels:
        return REFERENCE, None
    fallback = FALLBACK_REFERENCE if FALLBACK_REFERENCE in labels else sorted(labels)[0]
    return fallback, (f"this run has no {REFERENCE} measurement (the shadow-map techniques were not in its "
                      f"ladder), so the ratios are against {fallback} instead")


def ratio_text(m, cell, reference):
    ref = cell.get(reference) if reference else None
    if not ref or ref[COST] <= 0:
        return "–"
    return f"x{m[COST] / ref[COST]:.2f}"


def equal_time_rows(cells, budget_label, metric=None):
    """Per scene and light size: the budget's cost and MAE, and the lowest MAE of any occlusion-texture
    setting whose cost is within that budget."""
    rows = []
    for (scene, scale), cell in sorted(cells.items()):
        budget = cell.get(budget_label)
        if budget is None:
            continue
        within = [m for m in cell.values() if m["family"] == "occlusion" and m[COST] <= budget[COST]]
        best = min(within, key=lambda m: pen(m, metric)) if within else None
        cheapest = min((m for m in cell.values() if m["family"] == "occlusion"), key=lambda m: m[COST], default=None)
        if cheapest is None:  # no occlusion-texture setting in this run: nothing to compare
            continue
        rows.append((scene, scale, budget, best, cheapest))
    return rows


def equal_time_wins(cells, budget_label, metric):
    """(wins, losses, cells without an occlusion-texture setting in the budget) on that reference."""
    wins = losses = none = 0
    for _, _, budget, best, _ in equal_time_rows(cells, budget_label, metric):
        if best is None:
            none += 1
        elif pen(best, metric) < pen(budget, metric):
            wins += 1
        else:
            losses += 1
    return wins, losses, none


def mean(values):
    values = list(values)
    return sum(values) / len(values) if values else math.nan


def per_label_over_scenes(measurements):
    """label -> scale -> (mean cost, mean penumbra MAE, scenes)"""
    acc = defaultdict(lambda: defaultdict(list))
    family = {}
    for m in measurements:
        acc[m["label"]][m["light_scale"]].append(m)
        family[m["label"]] = m["family"]
    out = {}
    for label, scales in acc.items():
        out[label] = {s: (mean(x[COST] for x in ms), mean(pen(x) for x in ms), len(ms)) for s, ms in scales.items()}
    return out, family


# ---- figures ------------------------------------------------------------------------------------

def make_figures(results, directory, suffix=""):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.image as mpimg

    fig_dir = os.path.join(directory, "figures")
    os.makedirs(fig_dir, exist_ok=True)
    measurements = results["measurements"]
    cells = by_cell(measurements)
    scenes = [s["name"] for s in results["scenes"]]
    scales = results["meta"]["light_scales"]
    families = sorted({m["family"] for m in measurements})
    colors = {f: plt.get_cmap("tab10")(i) for i, f in enumerate(families)}
    written = []

    # Pareto fronts: one figure per scene, one panel per light size.
    for scene in scenes:
        cols = min(3, len(scales))
        rows = math.ceil(len(scales) / cols)
        fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.4 * rows), squeeze=False)
        for i, scale in enumerate(scales):
            ax = axes[i // cols][i % cols]
            cell = list(cells.get((scene, scale), {}).values())
            for f in families:
                pts = [m for m in cell if m["family"] == f]
                ax.scatter([m[COST] for m in pts], [pen(m) for m in pts], s=18, color=colors[f], label=family_name(f))
            front = pareto_front(cell)
            ax.plot([m[COST] for m in front], [pen(m) for m in front], color="black", lw=1, ls="--")
            for m in front:
                ax.annotate(m["label"], (m[COST], pen(m)), fontsize=6, xytext=(3, 3), textcoords="offset points")
            ax.set_xscale("log")
            ax.set_title(f"{scene}, light {fmt_scale(scale)}", fontsize=9)
            ax.set_xlabel("frame shadow cost, ms (log)", fontsize=8)
            ax.set_ylabel(f"penumbra MAE ({metric_name()})", fontsize=8)
            ax.tick_params(labelsize=7)
            ax.grid(True, which="both", alpha=0.3)
        for j in range(len(scales), rows * cols):
            axes[j // cols][j % cols].axis("off")
        axes[0][0].legend(fontsize=7)
        fig.suptitle(f"Pareto front (dashed), {scene}{', under the sun' if suffix else ''}: time against penumbra MAE "
                     f"({metric_name()} reference)", fontsize=10)
        fig.tight_layout(rect=(0, 0, 1, 0.96))
        path = os.path.join(fig_dir, f"pareto_{scene}{suffix}.png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)

    # Cost and quality against light size, per setting (mean over scenes).
    summary, family = per_label_over_scenes(measurements)
    fig, (ax_cost, ax_mae) = plt.subplots(1, 2, figsize=(11, 4.2))
    markers = ["o", "s", "^", "D", "v", "P", "X"]
    label_colors = plt.get_cmap("tab20")
    for i, label in enumerate(sorted(summary, key=lambda l: (family[l], l))):
        pts = sorted(summary[label].items())
        style = dict(marker=markers[families.index(family[label]) % len(markers)], ms=4, color=label_colors(i % 20),
                     ls="-" if family[label] == "occlusion" else "--", label=label)
        xs = [s for s, _ in pts]
        ax_cost.plot(xs, [v[0] for _, v in pts], **style)
        ax_mae.plot(xs, [v[1] for _, v in pts], **style)
    for ax, title, ylabel in ((ax_cost, "cost against light size", "frame shadow cost, ms (mean over scenes)"),
                              (ax_mae, "penumbra MAE against light size", f"penumbra MAE ({metric_name()}, mean over scenes)")):
        ax.set_xscale("log", base=2)
        ax.set_xticks(scales, [fmt_scale(x) for x in scales])
        ax.set_xlabel("light size, multiple of the scene's default", fontsize=8)
        ax.set_ylabel(ylabel, fontsize=8)
        ax.set_title(title, fontsize=10)
        ax.grid(True, which="both", alpha=0.3)
        ax.tick_params(labelsize=7)
    ax_cost.set_yscale("log")
    ax_mae.legend(fontsize=6, ncol=2)
    ax_cost.text(0.01, 0.01, "solid: occlusion textures, dashed: shadow-map techniques", fontsize=6,
                 transform=ax_cost.transAxes)
    fig.tight_layout()
    path = os.path.join(fig_dir, f"cost_vs_light_size{suffix}.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    written.append(path)

    # Montage per light size: rows = scene × (visibility, error), columns = truth + representative settings.
    reps = []
    for m in measurements:
        if m.get("images") and m["label"] not in reps:
            reps.append(m["label"])
    for scale in scales:
        rows = [(scene, kind) for scene in scenes for kind in ("visibility", "error")]
        fig, axes = plt.subplots(len(rows), len(reps) + 1, figsize=(1.7 * (len(reps) + 1), 1.7 * len(rows)),
                                 squeeze=False)
        for r, (scene, kind) in enumerate(rows):
            cell = cells.get((scene, scale), {})
            for c, label in enumerate(["truth"] + reps):
                ax = axes[r][c]
                ax.set_xticks([])
                ax.set_yticks([])
                m = next((x for x in cell.values() if x.get("images")), None) if label == "truth" else cell.get(label)
                image = None
                if m and m.get("images"):
                    key = "truth" if label == "truth" else kind
                    if not (label == "truth" and kind == "error"):
                        image = os.path.join(directory, m["images"][key])
                if image and os.path.exists(image):
                    ax.imshow(mpimg.imread(image), cmap="gray", vmin=0, vmax=1, interpolation="nearest")
                else:
                    ax.axis("off")
                if r == 0:
                    ax.set_title(label, fontsize=6)
                if c == 0:
                    ax.set_ylabel(f"{scene}\n{kind}", fontsize=6)
                if kind == "error" and label != "truth" and m:
                    ax.set_xlabel(f"MAE {pen(m):.3f}", fontsize=6)
        fig.suptitle(f"{'sun' if suffix else 'light'} {fmt_scale(scale)}: visibility and signed error (red too bright, blue too dark, "
                     f"±0.25 saturates)", fontsize=8)
        fig.tight_layout(rect=(0, 0, 1, 0.985))
        path = os.path.join(fig_dir, f"montage_{fmt_scale(scale)}{suffix}.png")
        fig.savefig(path, dpi=110)
        plt.close(fig)
        written.append(path)
    return written


# ---- the report ---------------------------------------------------------------------------------

def write_report(results, directory, thresholds, figures):
    """report.md: the run, then the tables of each light (figures: light -> its figures)."""
    meta = results["meta"]
    measurements = results["measurements"]
    reference, reference_note = reference_label(measurements)
    out = []
    w = out.append

    w("# Penumbra: every technique against ray-traced truth\n")
    w(f"Command: `{meta['command']}` ({meta['set']} set), started {meta['started']}, "
      f"{meta['wall_s'] / 60:.1f} minutes.\n")
    w(f"Renderer: **{meta['renderer']}** ({meta['gl_version']}, EGL {meta['egl_platform']}). "
      f"Image {meta['image'][0]}×{meta['image'][1]}; ground truth: Embree, {meta['truth_rays_per_axis']}×"
      f"{meta['truth_rays_per_axis']} stratified rays per pixel at the same pixels; costs: median of "
      f"{meta['timed_runs']} timed runs after {meta['warmup_runs']} warm-up run.\n")
    if "llvmpipe" in meta["renderer"] or "softpipe" in meta["renderer"]:
        w("> **On llvmpipe only ratios mean something.** The milliseconds are the CPU time of Mesa's software "
          "rasteriser on a shared machine, not GPU time; they rank techniques roughly but do not predict a GPU. "
          f"Every cost is shown beside its ratio to {reference or 'the reference setting'} at the same scene and "
          "light size.\n")
    if meta["truth_rays_per_axis"] < 32:
        w(f"> This run's ground truth uses only {meta['truth_rays_per_axis']}×{meta['truth_rays_per_axis']} rays "
          "per pixel (a quick smoke run); the real comparison uses at least 32×32. Its numbers are noisy.\n")
    if reference_note:
        w(f"> Note: {reference_note}.\n")
    w("Definitions. *Cost* of a frame: the summed GL_TIME_ELAPSED of every pass of the technique's layout "
      "(shadow map or slicing, prefilter, shading over the G-buffer); the wall clock to `glFinish` is in the "
      "full table. *Penumbra pixels*: geometry pixels where the truth or the estimate is below "
      f"{meta['penumbra_threshold']}. *MAE/RMSE/p95*: of |estimate − truth|. Light sizes: multiples of each "
      "scene's default rectangle (2×2 for the built-in scenes).\n")
    w(f"Reference of the conclusions (*MAE* below): **{metric_name()}**, the {METRICS[METRIC]}. Beside it, the "
      f"penumbra MAE against the other references ({other_metrics()}); pixels that see none of the light are "
      "left out of the fair ones. `compare_report.py DIR --metric oriented` (or `visibility`) rebuilds the "
      "report on another reference.\n")
    w("Techniques in this run: " + ", ".join(
        f"{family_name(f)} ({sum(1 for l in {m['label'] for m in measurements if m['family'] == f})} settings)"
        for f in sorted({m["family"] for m in measurements})) + ".\n")

    skipped = results.get("skipped", [])
    if skipped:
        w("Skipped (a setting that cannot run under a light, or whose bake could not be made): " + "; ".join(
            f"{x['label']} on {x['scene']} under the {x['light']} light: {x['reason']}" for x in skipped) + ".\n")
    for light in lights_of(results):
        sub = for_light(results, light)
        if light == "rect" and len(lights_of(results)) > 1:
            w(f"# Under {LIGHT_TITLES['rect']}\n")
        if light != "rect":
            w(f"# Under {LIGHT_TITLES.get(light, light)}\n")
            w("Each scene's sun (5 × the real sun's angular diameter for the built-in scenes) on a path through it "
              "at t = 0.5, which occlusion interval maps bake; light sizes are multiples of its angular diameter, "
              "and for the flicker the sun moves along its path by "
              f"{meta.get('sun_flicker_step_t', 0):g} in t per frame. Every table below is of the sun alone.\n")
        write_light(sub, directory, thresholds, figures.get(light, []), w,
                    "" if light == "rect" else f" (under {LIGHT_TITLES.get(light, light)})")

    # three.js's own shadows against the same kind of truth, when targets/web/three_peers.mjs
    # --markdown DIR/three_peers.md wrote its tables here (web/three/README.md says how).
    write_three_peers(directory, w)

    with open(os.path.join(directory, "report.md"), "w") as f:
        f.write("\n".join(out))


def write_light(results, directory, thresholds, figures, w, title):
    """The report's tables for the measurements of one light; `title` follows every heading."""
    meta = results["meta"]
    measurements = results["measurements"]
    cells = by_cell(measurements)
    scales = meta["light_scales"]
    reference, _ = reference_label(measurements)
    light = light_of(measurements[0]) if measurements else "rect"

    # The conclusions in one place: the chosen (fair) reference first, the others after it.
    w(f"## Summary{title}\n")
    for budget_label in EQUAL_TIME_BUDGETS:
        if not equal_time_rows(cells, budget_label):
            continue
        counts = {k: equal_time_wins(cells, budget_label, k) for k in METRICS}
        total = sum(counts[METRIC])
        wins, losses, none = counts[METRIC]
        w(f"- At the cost of {budget_label}, on the **{metric_name()}** reference, an occlusion-texture setting has "
          f"the lower penumbra MAE in **{wins} of {total}** scene × light cells (higher in {losses}, none within "
          f"the cost in {none}). On the other references: " + "; ".join(
              f"{metric_name(k)} {counts[k][0]} of {sum(counts[k])}" for k in METRICS if k != METRIC) + ".")
    key = [label for label in KEY_SETTINGS if any(m["label"] == label for m in measurements)]
    for label in key:
        at_default = [m for m in measurements if m["label"] == label and m["light_scale"] == min(scales)]
        if at_default:
            w(f"- {label}{' (the default configuration)' if label == DEFAULT_SETTING else ''} at light "
              f"{fmt_scale(min(scales))}: mean penumbra MAE **{mean(pen(m) for m in at_default):.4f}** "
              f"({metric_name()}) over {len(at_default)} scenes; " + "; ".join(
                  f"{metric_name(k)} {mean(pen(m, k) for m in at_default):.4f}" for k in METRICS if k != METRIC) + ".")
    w("")

    # Per scene and per mesh, at the default light.
    write_scene_tables(results, w, title)

    # Equal time.
    w(f"## Equal time{title}\n")
    w("At the cost of a PCSS setting (same scene, same light size): the lowest penumbra MAE that any "
      "occlusion-texture setting reaches within that cost, beside the PCSS setting's own MAE.\n")
    for budget_label in EQUAL_TIME_BUDGETS:
        rows = equal_time_rows(cells, budget_label)
        w(f"### At the cost of {budget_label}\n")
        if not rows:
            w(f"Empty: results.json has no {budget_label} measurement, so there is no budget to compare at "
              "(the shadow-map techniques were not in this run's ladder), or no occlusion-texture setting to "
              "compare.\n")
            continue
        w(f"| scene | light | {budget_label} ms | its MAE ({other_metrics()}) | best OT within that cost | "
          f"OT ms (ratio) | OT MAE ({other_metrics()}) | OT wins |")
        w("|---|---|---|---|---|---|---|---|")
        wins = losses = none = 0
        for scene, scale, budget, best, cheapest in rows:
            if best is None:
                none += 1
                w(f"| {scene} | {fmt_scale(scale)} | {fmt_ms(budget[COST])} | {pen(budget):.4f} ({fair_text(budget)}) | "
                  f"none: the cheapest, {cheapest['label']}, costs {fmt_ms(cheapest[COST])} "
                  f"(x{cheapest[COST] / budget[COST]:.2f}) | – | {pen(cheapest):.4f} ({fair_text(cheapest)}) | – |")
                continue
            win = pen(best) < pen(budget)
            wins += win
            losses += not win
            w(f"| {scene} | {fmt_scale(scale)} | {fmt_ms(budget[COST])} | {pen(budget):.4f} ({fair_text(budget)}) | "
              f"{best['label']} | {fmt_ms(best[COST])} (x{best[COST] / budget[COST]:.2f}) | {pen(best):.4f} "
              f"({fair_text(best)}) | {'yes' if win else 'no'} |")
        w(f"\nOf {len(rows)} scene × light cells, an occlusion-texture setting within the cost of {budget_label} "
          f"has the lower penumbra MAE in **{wins}**, the higher in **{losses}**, and none fits the budget in "
          f"**{none}**.\n")

    # Light size.
    summary, family = per_label_over_scenes(measurements)
    lo, hi = min(scales), max(scales)
    w(f"## Light size{title}\n")
    w(f"Cost at {fmt_scale(hi)} over cost at {fmt_scale(lo)} per setting (fixed settings; the ratio is the mean "
      "over scenes of each scene's ratio), and the penumbra MAE at both sizes (mean over scenes).\n")
    w(f"| setting | technique | ms at {fmt_scale(lo)} | ms at {fmt_scale(hi)} | cost {fmt_scale(hi)} / {fmt_scale(lo)} | "
      f"MAE at {fmt_scale(lo)} | MAE at {fmt_scale(hi)} |")
    w("|---|---|---|---|---|---|---|")
    per_scene_ratio = defaultdict(list)
    for (scene, scale), cell in cells.items():
        if scale != hi:
            continue
        for label, m in cell.items():
            base = cells.get((scene, lo), {}).get(label)
            if base and base[COST] > 0:
                per_scene_ratio[label].append(m[COST] / base[COST])
    for label in sorted(summary, key=lambda l: (family[l], summary[l].get(lo, (math.inf,))[0])):
        s = summary[label]
        if lo not in s or hi not in s:
            continue
        w(f"| {label} | {family_name(family[label])} | {fmt_ms(s[lo][0])} | {fmt_ms(s[hi][0])} | "
          f"x{mean(per_scene_ratio[label]):.2f} | {s[lo][1]:.4f} | {s[hi][1]:.4f} |")
    w("")
    w("The cheapest setting of each technique whose penumbra MAE (mean over scenes) stays at or below a fixed "
      "threshold at each light size, with its mean cost in ms and its MAE; '–' gives the technique's best MAE "
      "when no setting reaches the threshold.\n")
    w("| technique | MAE ≤ | " + " | ".join(fmt_scale(s) for s in scales) + " |")
    w("|---|---|" + "---|" * len(scales))
    for f in sorted(set(family.values())):
        for threshold in thresholds:
            cells_text = []
            for s in scales:
                options = [(v[s][0], label, v[s][1]) for label, v in summary.items() if family[label] == f and s in v]
                ok = [o for o in options if o[2] <= threshold]
                if ok:
                    cost, label, mae = min(ok)
                    cells_text.append(f"{label} ({fmt_ms(cost)} ms, {mae:.3f})")
                elif options:
                    best = min(options, key=lambda o: o[2])
                    cells_text.append(f"– (best {best[1]}: {best[2]:.3f})")
                else:
                    cells_text.append("not run")
            w(f"| {family_name(f)} | {threshold:g} | " + " | ".join(cells_text) + " |")
    w("")

    write_quality_by_light_size(results, measurements, scales, w, title)

    # Flicker.
    w(f"## Temporal stability{title}\n")
    flicker = results["flicker"]
    if flicker:
        motion = (f"The sun (default size) moves along its path by {meta.get('sun_flicker_step_t', 0):g} in t per frame"
                  if light == "sun" else
                  f"The light (default size) moves along its u axis by {meta['flicker_step_of_ground_span'] * 100:g} % "
                  "of the scene's ground span per frame")
        w(f"{motion} over {meta['flicker_frames']} frames. Excess flicker = mean |Δ "
          "visibility| between consecutive frames over geometry pixels, minus the same for the truth (the shadow's "
          "real motion). Positive: the technique changes more than the truth does.\n")
        labels = []
        for f in flicker:
            if f["label"] not in labels:
                labels.append(f["label"])
        scenes = [s["name"] for s in results["scenes"]]
        w("| setting | " + " | ".join(f"{s} (truth {next(x['truth_delta'] for x in flicker if x['scene'] == s):.4f})"
                                      for s in scenes if any(x["scene"] == s for x in flicker)) + " | mean excess |")
        w("|---|" + "---|" * (len([s for s in scenes if any(x['scene'] == s for x in flicker)]) + 1))
        for label in labels:
            rows = {x["scene"]: x for x in flicker if x["label"] == label}
            w(f"| {label} | " + " | ".join(f"{rows[s]['excess']:+.4f}" if s in rows else "–"
                                           for s in scenes if any(x["scene"] == s for x in flicker)) +
              f" | **{mean(r['excess'] for r in rows.values()):+.4f}** |")
        w("")
    else:
        w("No flicker measurement in this run.\n")

    # Where the time goes.
    w(f"## Where the time goes{title}\n")
    w(f"Mean over scenes and light sizes of the GPU time of the passes from the light (shadow map or slicing and "
      f"prefilter: independent of the image size) and of the screen pass over the {meta['image'][0]}×"
      f"{meta['image'][1]} G-buffer (proportional to the pixels shaded). At a larger image the screen share grows "
      "by the ratio of pixel counts; the light passes stay.\n")
    w("| setting | technique | light passes ms | screen pass ms | screen share | textures MiB |")
    w("|---|---|---|---|---|---|")
    split = defaultdict(list)
    for m in measurements:
        screen = m["passes"][-1]["gpu_ms"]
        split[m["label"]].append((sum(p["gpu_ms"] for p in m["passes"][:-1]), screen, m["texture_bytes"]))
    for label in sorted(split, key=lambda l: (family[l], mean(x[0] + x[1] for x in split[l]))):
        light_ms, screen_ms = mean(x[0] for x in split[label]), mean(x[1] for x in split[label])
        share = screen_ms / (light_ms + screen_ms) if light_ms + screen_ms > 0 else 0
        w(f"| {label} | {family_name(family[label])} | {fmt_ms(light_ms)} | {fmt_ms(screen_ms)} | {share * 100:.0f} % | "
          f"{split[label][0][2] / 2**20:.1f} |")
    w("")

    # Signed error.
    w(f"## Too bright or too dark{title}\n")
    bias_metric = metric_name() if has_bias(measurements) else metric_name("visibility")
    w(f"Mean signed error over penumbra pixels (estimate − truth, against the {bias_metric} reference), mean over "
      "scenes: positive where a setting is too bright (light leaking through or around occluders), negative "
      "where it is too dark (occlusion counted twice, penumbrae too wide). The montages show where.\n")
    w("| setting | " + " | ".join(fmt_scale(s) for s in scales) + " |")
    w("|---|" + "---|" * len(scales))
    biases = defaultdict(lambda: defaultdict(list))
    for m in measurements:
        biases[m["label"]][m["light_scale"]].append(bias(m))
    for label in sorted(biases, key=lambda l: (family[l], l)):
        w(f"| {label} | " + " | ".join(f"{mean(biases[label][s]):+.3f}" if biases[label][s] else "–" for s in scales) + " |")
    w("")

    # Pareto fronts.
    w(f"## Pareto fronts{title}\n")
    w("Per scene and light size, the settings no other setting beats on both cost and penumbra MAE, cheapest "
      "first.\n")
    w("| scene | light | front: setting (ms, ratio, MAE) |")
    w("|---|---|---|")
    for (scene, scale), cell in sorted(cells.items()):
        front = pareto_front(cell.values())
        w(f"| {scene} | {fmt_scale(scale)} | " + "; ".join(
            f"{m['label']} ({fmt_ms(m[COST])}, {ratio_text(m, cell, reference)}, {pen(m):.4f})" for m in front) + " |")
    w("")

    # Figures.
    w(f"## Figures{title}\n")
    for path in figures:
        rel = os.path.relpath(path, directory)
        w(f"![{os.path.basename(path)}]({rel})\n")

    # Every measurement.
    w(f"## Every measurement{title}\n")
    w(f"GPU: summed timer queries; wall: to glFinish (shadow passes, shading, total); ratio: GPU cost against "
      f"{reference or 'the reference'} at the same scene and light; texture memory from the layout's textures.\n")
    w("| scene | light | setting | GPU ms (fastest) | ratio | wall ms (shadow + shading = total) | textures MiB | "
      f"penumbra MAE / RMSE / p95 (px) | all MAE / RMSE / p95 (px) | penumbra MAE {other_metrics()} | penumbra bias | "
      "passes, GPU ms |")
    w("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for (scene, scale), cell in sorted(cells.items()):
        for m in sorted(cell.values(), key=lambda m: (m["family"], m[COST])):
            q, wall = quality(m), m["wall_ms"]
            passes = ", ".join(f"{p['name']}{'×' + str(p['instances']) if p['instances'] > 1 else ''} "
                               f"{fmt_ms(p['gpu_ms'])}" for p in m["passes"])
            w(f"| {scene} | {fmt_scale(scale)} | {m['label']} | {fmt_ms(m[COST])} ({fmt_ms(m['gpu_ms_fastest'])}) | "
              f"{ratio_text(m, cell, reference)} | "
              f"{fmt_ms(wall['shadow_passes'])} + {fmt_ms(wall['shading'])} = {fmt_ms(wall['total'])} | "
              f"{m['texture_bytes'] / 2**20:.1f} | {q['penumbra']['mae']:.4f} / {q['penumbra']['rmse']:.4f} / "
              f"{q['penumbra']['p95']:.3f} ({q['penumbra']['pixels']}) | {q['all']['mae']:.4f} / "
              f"{q['all']['rmse']:.4f} / {q['all']['p95']:.3f} ({q['all']['pixels']}) | {fair_text(m)} | "
              f"{bias(m):+.3f} | {passes} |")
    w("")
    truths = {s["name"]: [t for t in s["truth"] if t.get("light", "rect") == light] for s in results["scenes"]}
    w("Ground truth per scene (computed or read from the cache): " + "; ".join(
        f"{name}: {sum(t['ms'] for t in ts) / 1000:.1f} s for {len(ts)} images "
        f"({sum(1 for t in ts if t['cached'])} cached)" for name, ts in truths.items() if ts) + ".\n")
    bakes = [b for b in results.get("bakes", []) if b.get("light") == light]
    if bakes:
        w("Bakes of occlusion interval maps: a precomputation like the truth, never in the frame's cost (one per "
          "scene and setting, cached in the run's cache/oim).\n")
        w("| scene | setting | maps | intervals | samples along the path | bake s | cached | rays | file MiB |")
        w("|---|---|---|---|---|---|---|---|---|")
        for b in bakes:
            w(f"| {b['scene']} | {b['label']} | {b['resolution']}² | {b['intervals']} | {b['samples']} | "
              f"{b['bake_ms'] / 1000:.2f} | {'yes' if b['from_cache'] else 'no'} | {b['rays']} | "
              f"{b['file_bytes'] / 2**20:.2f} |")
        w("")


def write_quality_by_light_size(results, measurements, scales, w, title=""):
    """Mean penumbra MAE and mean signed error per setting and light size, built-in scenes and meshes apart."""
    kinds = {s["name"]: s.get("kind", "built-in") == "built-in" for s in results["scenes"]}
    w(f"## Quality by light size{title}\n")
    # results.json from before the bench recorded each reference's signed error holds the whole light's alone
    signed_against = metric_name() if has_bias(measurements) else metric_name("visibility")
    w(f"Per setting, the mean over scenes of the penumbra MAE against the {metric_name()} reference / the mean "
      f"signed error (estimate − truth; positive: too bright) against the {signed_against} reference at each light "
      "size, the built-in scenes and the meshes (files and the corpus) apart.\n")
    for group_title, built_in in (("Built-in scenes", True), ("Meshes (files and the corpus)", False)):
        group = [m for m in measurements if kinds.get(m["scene"], True) == built_in]
        if not group:
            continue
        w(f"{group_title}:\n")
        w("| setting | technique | " + " | ".join(fmt_scale(s) for s in scales) + " |")
        w("|---|---|" + "---|" * len(scales))
        acc = defaultdict(lambda: defaultdict(list))
        family = {}
        for m in group:
            acc[m["label"]][m["light_scale"]].append(m)
            family[m["label"]] = m["family"]
        for label in sorted(acc, key=lambda l: (family[l], mean(pen(x) for x in acc[l][min(scales)]))):
            cells_text = []
            for s in scales:
                ms = acc[label][s]
                cells_text.append(f"{mean(pen(x) for x in ms):.3f} / {mean(bias(x) for x in ms):+.3f}" if ms else "–")
            w(f"| {label} | {family_name(family[label])} | " + " | ".join(cells_text) + " |")
        w("")


def write_three_peers(directory, w):
    """three.js's tables, when targets/web/three_peers.mjs --markdown DIR/three_peers.md wrote them."""
    three = os.path.join(directory, "three_peers.md")
    if os.path.isfile(three):
        w("## three.js's shadow maps and the three.js add-on against the truth\n")
        w("From `targets/web/three_peers.mjs` (headless chromium): the scene rebuilt in three.js, "
          "three's PCFSoftShadowMap and VSMShadowMap from a SpotLight where the rectangle is, "
          "Penumbra's add-on and the desktop runtime, against the bundle's Embree truth.\n")
        with open(three) as f:
            w(f.read())


def write_scene_tables(results, w, title=""):
    """Per built-in scene and per mesh (files and the corpus): the key settings at the smallest light
    size — penumbra MAE and p95, all-pixel MAE (chosen reference), cost and its ratio to PCSS 16/16."""
    measurements = results["measurements"]
    scale = min(results["meta"]["light_scales"])
    cells = by_cell(measurements)
    labels = [label for label in KEY_SETTINGS if any(m["label"] == label for m in measurements)]
    if DEFAULT_SETTING not in labels:  # e.g. --quick: its occlusion-texture settings stand in for the default
        labels = list(dict.fromkeys(m["label"] for m in measurements if m["family"] == "occlusion")) + labels
    if not labels:
        labels = list(dict.fromkeys(m["label"] for m in measurements))
    reference, _ = reference_label(measurements)
    built_in = [s for s in results["scenes"] if s.get("kind", "built-in") == "built-in"]
    meshes = [s for s in results["scenes"] if s.get("kind", "built-in") != "built-in"]
    w(f"## Per scene and mesh{title}\n")
    w(f"At each scene's default light ({fmt_scale(scale)}), the default configuration ({DEFAULT_SETTING}) and "
      f"the PCSS settings shipping engines use: penumbra MAE and p95 and all-pixel MAE against the "
      f"{metric_name()} reference; cost: the GPU time of every pass of the frame (light passes and the screen "
      f"pass), and its ratio to {reference or 'the reference'} on the same scene (on llvmpipe only the ratio "
      "means something). Mean rows: over the scenes of the table.\n")
    for title, scenes in (("Built-in scenes", built_in), ("Meshes (files and the corpus)", meshes)):
        if not scenes:
            continue
        w(f"### {title}\n")
        if scenes is meshes:
            grounded = sum(1 for s in scenes if s.get("ground", any(m.get("ground") for m in measurements
                                                                  if m["scene"] == s["name"])))
            w(f"{grounded} of {len(scenes)} on a floor under their bounds (+2 triangles; `--no-ground` drops it).\n")
        w("| scene | triangles | setting | penumbra MAE | penumbra p95 | all-pixel MAE | cost ms | ratio | "
          f"penumbra MAE {other_metrics()} |")
        w("|---|---|---|---|---|---|---|---|---|")
        per_label = defaultdict(list)
        for s in scenes:
            cell = cells.get((s["name"], scale), {})
            for label in labels:
                m = cell.get(label)
                if not m:
                    continue
                per_label[label].append(m)
                q = quality(m)
                w(f"| {s['name']} | {s['triangles']} | {label} | {q['penumbra']['mae']:.4f} | {q['penumbra']['p95']:.3f} | "
                  f"{q['all']['mae']:.4f} | {fmt_ms(m[COST])} | {ratio_text(m, cell, reference)} | {fair_text(m)} |")
        for label in labels:
            ms = per_label[label]
            if not ms:
                continue
            ratios = [m[COST] / cells[(m["scene"], scale)][reference][COST] for m in ms
                      if reference in cells[(m["scene"], scale)] and cells[(m["scene"], scale)][reference][COST] > 0]
            w(f"| **mean** ({len(ms)}) | | {label} | **{mean(pen(m) for m in ms):.4f}** | "
              f"{mean(quality(m)['penumbra']['p95'] for m in ms):.3f} | {mean(quality(m)['all']['mae'] for m in ms):.4f} | "
              f"{fmt_ms(mean(m[COST] for m in ms))} | {'x%.2f' % mean(ratios) if ratios else '–'} | "
              f"{' / '.join(f'{mean(pen(m, k) for m in ms):.3f}' for k in METRICS if k != METRIC)} |")
        w("")
    corpus = [s for s in meshes if s.get("corpus")]
    if corpus:
        w("Corpus meshes (scripts/get_corpus.sh): " + "; ".join(
            f"{s['name']}: {s['triangles']} triangles, {s['corpus']['source']}, licence: {s['corpus']['licence']}"
            for s in corpus) + ".\n")


# ---- the CI check -------------------------------------------------------------------------------

def non_finite(value, path="results"):
    """Paths of every number in the JSON value that is null (NaN when written), infinite or NaN."""
    if value is None:
        return [path]
    if isinstance(value, bool) or isinstance(value, str):
        return []
    if isinstance(value, (int, float)):
        return [] if math.isfinite(value) else [path]
    if isinstance(value, list):
        return [p for i, v in enumerate(value) for p in non_finite(v, f"{path}[{i}]")]
    if isinstance(value, dict):
        return [p for k, v in value.items() for p in non_finite(v, f"{path}.{k}")]
    return []


def check(directory):
    problems = []
    results = load(directory)
    bad = non_finite(results)
    if bad:
        problems.append(f"{len(bad)} numbers in results.json are not finite, e.g. {bad[0]}")
    if not results["measurements"]:
        problems.append("results.json has no measurements")
    if not results["flicker"]:
        problems.append("results.json has no flicker measurement")
    report = os.path.join(directory, "report.md")
    if not os.path.exists(report) or os.path.getsize(report) == 0:
        problems.append("report.md is missing or empty")
    else:
        text = open(report).read()
        for heading in ("## Summary", "## Per scene and mesh", "## Equal time", "## Light size", "## Temporal stability", "## Too bright or too dark",
                        "## Pareto fronts"):
            if heading not in text:
                problems.append(f"report.md has no '{heading}' section")
    expected = [name for light in lights_of(results) for name in
                [f"pareto_{s['name']}{suffix_of(light)}.png" for s in results["scenes"]] +
                [f"cost_vs_light_size{suffix_of(light)}.png"] +
                [f"montage_{fmt_scale(s)}{suffix_of(light)}.png" for s in results["meta"]["light_scales"]]]
    for name in expected:
        path = os.path.join(directory, "figures", name)
        if not os.path.exists(path) or os.path.getsize(path) < 1000:
            problems.append(f"figure {name} is missing or empty")
        elif open(path, "rb").read(8) != b"\x89PNG\r\n\x1a\n":
            problems.append(f"figure {name} is not a PNG file")
    for m in results["measurements"]:
        for key in ("visibility", "error"):
            if m.get("images") and not os.path.exists(os.path.join(directory, m["images"][key])):
                problems.append(f"image {m['images'][key]} is missing")
    for p in problems:
        print(f"check: {p}", file=sys.stderr)
    if not problems:
        print(f"check: {directory}: report, {len(expected)} figures, {len(results['measurements'])} measurements, "
              "every number finite")
    return 1 if problems else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("directory", help="the folder holding results.json (penumbra-bench-compare --out)")
    parser.add_argument("--mae-thresholds", default="0.1,0.15,0.2",
                        help="penumbra MAEs the light-size table keeps each technique under (default 0.1,0.15,0.2)")
    parser.add_argument("--metric", choices=list(METRICS), default="shaded",
                        help="the reference the conclusions use (default shaded, the shaded image's error: the "
                             "irradiance error weighed by the light each pixel receives; the others are shown beside "
                             "it: irradiance, oriented, and visibility of the whole light)")
    parser.add_argument("--check", action="store_true", help="check an existing report instead of writing one")
    args = parser.parse_args()
    global METRIC
    METRIC = args.metric
    if not os.path.exists(os.path.join(args.directory, "results.json")):
        print(f"error: {args.directory}/results.json not found; run penumbra-bench-compare --out "
              f"{args.directory} first", file=sys.stderr)
        return 2
    if args.check:
        return check(args.directory)
    results = load(args.directory)
    if METRIC == "shaded" and not all("shaded" in m["quality"] for m in results["measurements"]):
        print("note: these results predate the shaded reference; the conclusions use irradiance", file=sys.stderr)
        METRIC = "irradiance"
        del METRICS["shaded"]
    try:
        figures = {light: make_figures(for_light(results, light), args.directory, suffix_of(light))
                   for light in lights_of(results)}
    except ImportError as e:
        print(f"error: matplotlib is missing ({e}); install Debian's python3-matplotlib (scripts/setup.sh)",
              file=sys.stderr)
        return 1
    try:
        thresholds = [float(t) for t in args.mae_thresholds.split(",")]
    except ValueError:
        print(f"error: --mae-thresholds: '{args.mae_thresholds}' is not a list of numbers, e.g. 0.05,0.1",
              file=sys.stderr)
        return 2
    write_report(results, args.directory, thresholds, figures)
    print(f"wrote {args.directory}/report.md and {sum(len(f) for f in figures.values())} figures in "
          f"{args.directory}/figures/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
