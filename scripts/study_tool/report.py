"""The end of a study: a printed summary (also summary.txt) and plots beside the results —
creep-curve families (creep_curves.png/.svg) and, when models are compared against the
reference model, error maps (error_map.png/.svg)."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the file-only backend)
import numpy as np  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402

MODEL = "creep_force_model"
# Symbols of the usual axes.
LABELS = {"friction_coefficient": "μ", "creepage_longitudinal": "ξ", "creepage_lateral": "η", "spin_creepage": "φ"}
# Derived columns a plot may use besides the FMU's variables (spec.DERIVED: the columns each needs).
DERIVED = {"a_over_b": ("a/b", lambda frame: frame["semi_axis_a"] / frame["semi_axis_b"]),
           "adhesion_coefficient": ("adhesion coefficient |F|/Q",
                                    lambda frame: np.hypot(frame["force_longitudinal"], frame["force_lateral"])
                                    / frame["normal_force"])}
ERROR_FLOOR = 1e-7


def with_derived(frame):
    frame = frame.copy()
    for name, (_, compute) in DERIVED.items():
        try:
            frame[name] = compute(frame)
        except KeyError:  # an output it needs is not kept
            pass
    return frame


def symbol(name):
    """Short name for legends."""
    return DERIVED[name][0] if name in DERIVED else LABELS.get(name, name)


def label(name):
    """Axis label: the symbol and the variable's name."""
    return f"{LABELS[name]} ({name})" if name in LABELS else symbol(name)


def panels(frame):
    """(title, rows) per case and model, in the study's order."""
    result = []
    for case in dict.fromkeys(frame["case"]):
        for model in dict.fromkeys(frame[MODEL]):
            rows = frame[(frame["case"] == case) & (frame[MODEL] == model)]
            result.append((f"{case}: {model}" if case else model, rows))
    return result


def geometric(values):
    values = np.asarray(values, dtype=float)
    return bool(len(values) > 2 and np.all(values > 0) and values.max() / values.min() > 50)


def creep_curves(frame, plot, out):
    """One panel per case × model and output: the output over plot.x, one line per value of
    plot.family; where several scenes share (family, x) — random samples or further grid axes —
    the line is their median and the band spans their 5 % to 95 % quantiles."""
    x = plot["x"]
    if x is None:
        return []
    ok = with_derived(frame[frame["status"] == "ok"])
    if ok.empty:
        return []
    groups = panels(ok)
    outputs = plot["y"]
    figure, axes = plt.subplots(len(outputs), len(groups), squeeze=False, sharex=True,
                                figsize=(3.6 * len(groups) + 1, 3.0 * len(outputs) + 0.6))
    family = plot["family"]
    family_values = list(dict.fromkeys(ok[family].itertuples(index=False, name=None))) if family else [()]
    # Colour by the first family variable, line style by the rest (a colour per combination
    # would make nine shades of one colour map).
    first = list(dict.fromkeys(v[:1] for v in family_values))
    rest = list(dict.fromkeys(v[1:] for v in family_values))
    palette = plt.cm.viridis(np.linspace(0, 0.85, max(len(first), 1)))
    styles = ["-", "--", ":", "-."]
    colours = [palette[first.index(v[:1])] for v in family_values]
    linestyles = [styles[rest.index(v[1:]) % len(styles)] for v in family_values]
    banded = False
    for column, (title, rows) in enumerate(groups):
        for row, output in enumerate(outputs):
            ax = axes[row][column]
            for colour, linestyle, values in zip(colours, linestyles, family_values):
                subset = rows
                for name, value in zip(family, values):
                    subset = subset[subset[name] == value]
                if subset.empty:
                    continue
                statistics = subset.groupby(x)[output].quantile([0.05, 0.5, 0.95]).unstack()
                name = ", ".join(f"{symbol(n)} = {v:.4g}" if isinstance(v, float) else f"{symbol(n)} = {v}"
                                 for n, v in zip(family, values)) or None
                ax.plot(statistics.index, statistics[0.5], color=colour, linestyle=linestyle, label=name, linewidth=1.2)
                if (subset.groupby(x)[output].size() > 1).any():
                    banded = True
                    ax.fill_between(statistics.index, statistics[0.05], statistics[0.95], color=colour, alpha=0.2, linewidth=0)
            if geometric(ok[x]):
                ax.set_xscale("log")
            ax.grid(True, alpha=0.3)
            if row == 0:
                ax.set_title(title, fontsize=9)
            if row == len(outputs) - 1:
                ax.set_xlabel(label(x))
            if column == 0:
                ax.set_ylabel(label(output))
    if family:
        axes[0][0].legend(fontsize=7)
    if banded:
        figure.suptitle("lines: median, bands: 5 % to 95 % of the scenes at each point", fontsize=9)
    figure.tight_layout()
    return save(figure, out / "creep_curves")


def errors_against_reference(frame, study, output):
    """Per model other than the reference: each scene's |output - reference's| / (mu Q), matched on
    every other column (case, sample, every input and parameter). mu Q, the friction limit, makes
    errors comparable across the grid and finite where the force passes through zero."""
    reference = study["reference_model"]
    ok = with_derived(frame[frame["status"] == "ok"])
    if reference not in set(ok[MODEL]):
        return {}
    keys = [c for c in frame.columns if c not in set(study["outputs"]) | {"scene", MODEL, "status", "message"}]
    base = ok[ok[MODEL] == reference].set_index(keys)[output]
    limit = (ok["friction_coefficient"] * ok["normal_force"]).abs()
    result = {}
    for model in dict.fromkeys(ok[MODEL]):
        if model == reference:
            continue
        rows = ok[ok[MODEL] == model]
        values = rows.set_index(keys)[output]
        matched = base.reindex(values.index).to_numpy()
        error = np.abs(values.to_numpy() - matched) / limit[rows.index].to_numpy()
        table = rows.copy()
        table["error"] = error
        result[model] = table
    return result


def error_map(frame, study, out):
    spec = study["plot"]["error_map"]
    if spec is None:
        return [], {}
    errors = errors_against_reference(frame, study, spec["output"])
    if not errors or all(t["error"].isna().all() for t in errors.values()):
        return [], errors
    figure, axes = plt.subplots(1, len(errors), squeeze=False, figsize=(3.6 * len(errors) + 1.4, 3.8),
                                layout="constrained")
    every = np.concatenate([t["error"].to_numpy() for t in errors.values()])
    worst = max(np.nanmax(every), 10 * ERROR_FLOOR)
    positive = every[every > 0]
    best = np.nanmin(positive) if positive.size else ERROR_FLOOR
    norm = LogNorm(vmin=max(best, worst * 1e-4, ERROR_FLOOR), vmax=worst)
    for ax, (model, table) in zip(axes[0], errors.items()):
        grid = table.groupby([spec["y"], spec["x"]])["error"].max().unstack()
        image = ax.pcolormesh(np.arange(grid.shape[1] + 1), np.arange(grid.shape[0] + 1),
                              np.clip(grid.to_numpy(), norm.vmin, None), norm=norm, cmap="magma")
        ax.set_xticks(np.arange(grid.shape[1]) + 0.5, [f"{v:.3g}" for v in grid.columns], rotation=90, fontsize=7)
        ax.set_yticks(np.arange(grid.shape[0]) + 0.5, [f"{v:.3g}" for v in grid.index], fontsize=7)
        ax.set_xlabel(label(spec["x"]))
        if ax is axes[0][0]:
            ax.set_ylabel(label(spec["y"]))
        ax.set_title(f"{model} vs {study['reference_model']}", fontsize=9)
    figure.colorbar(image, ax=axes[0].tolist(), label=f"|Δ {spec['output']}| / (μQ), max over other axes")
    return save(figure, out / "error_map"), errors


def save(figure, stem):
    paths = [stem.with_suffix(".png"), stem.with_suffix(".svg")]
    for path in paths:
        figure.savefig(path, dpi=120)
    plt.close(figure)
    return paths


def summary(outcome, prepared, errors):
    frame = outcome.frame
    study = prepared.study
    lines = [f"study {study['name']!r} (key {prepared.key}): {len(frame)} scenes in {outcome.chunks} chunks of "
             f"up to {study['chunk_size']}; {outcome.computed} chunks computed, {outcome.reused} reused from an earlier run"]
    if outcome.computed:
        rate = f": {outcome.scenes_computed / outcome.seconds:.1f} scenes/s" if outcome.seconds > 0 else ""
        lines.append(f"computed {outcome.scenes_computed} scenes in {outcome.seconds:.2f} s{rate}; the workers' CPU "
                     f"time {1e3 * outcome.cpu_seconds / outcome.scenes_computed:.3g} ms per scene")
    failed = frame[frame["status"] != "ok"]
    lines.append(f"status: {len(frame) - len(failed)} ok, {len(failed)} failed")
    for message, count in failed["message"].value_counts().head(5).items():
        lines.append(f"  {count} × {message}")
    lines.append("outputs (ok scenes) per case and model: mean [min, max]")
    ok = with_derived(frame[frame["status"] == "ok"])
    for title, rows in panels(ok):
        for output in study["plot"]["y"]:
            values = rows[output]
            if len(values):
                lines.append(f"  {title:<28} {output:<28} {values.mean():.6g} [{values.min():.6g}, {values.max():.6g}]")
    x = study["plot"]["x"]
    if x is not None and ok["sample"].nunique() > 1:
        # Monte-Carlo: each sample's curve has one peak; its spread is what the draws change.
        lines.append(f"peak |output| over {x} per sample (ok scenes): median [5 %, 95 %] of the samples")
        others = [c for c in ok.columns if c not in set(study["outputs"]) | set(DERIVED)
                  | {"scene", "status", "message", x}]
        for title, rows in panels(ok):
            for output in study["plot"]["y"]:
                peaks = rows.assign(magnitude=rows[output].abs()).groupby(others)["magnitude"].max()
                q = peaks.quantile([0.05, 0.5, 0.95])
                lines.append(f"  {title:<28} {output:<28} {q[0.5]:.6g} [{q[0.05]:.6g}, {q[0.95]:.6g}] "
                             f"over {len(peaks)} samples")
    for model, table in errors.items():
        error = table["error"].dropna()
        unmatched = len(table) - len(error)
        lines.append(f"error of {model} against {study['reference_model']} in {study['plot']['error_map']['output']}, "
                     f"|Δ|/(μQ): max {error.max():.3g}, mean {error.mean():.3g} over {len(error)} scenes"
                     + (f" ({unmatched} without a reference value)" if unmatched else ""))
    return "\n".join(lines)


def report(outcome, prepared, out):
    """Writes the plots and summary.txt; returns the summary text and the plot paths."""
    plots = creep_curves(outcome.frame, prepared.study["plot"], out)
    maps, errors = error_map(outcome.frame, prepared.study, out)
    text = summary(outcome, prepared, errors)
    (out / "summary.txt").write_text(text + "\n")
    return text, plots + maps
