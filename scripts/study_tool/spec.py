"""Study files (TOML): reading, validation against the FMU's modelDescription, and expansion into
scenes.

The keys of a study file are listed in examples/studies/README.md, with three example studies
beside it. Scenes are case × model × grid point × random sample.

Every key is checked up front; a mistake raises StudyError naming the key (e.g. `grid.mu`).
"""

import dataclasses
import difflib
import hashlib
import itertools
import json
import math
import pathlib
import tomllib

import numpy as np
from fmpy import read_model_description

TOP_LEVEL = {"name", "description", "models", "outputs", "chunk_size", "steps", "step_size", "reference_model",
             "fixed", "grid", "random", "cases", "plot"}
MODEL_PARAMETER = "creep_force_model"
DISTRIBUTIONS = {
    "uniform": ("low", "high"),
    "loguniform": ("low", "high"),
    "normal": ("mean", "std"),
    "lognormal": ("mean", "sigma"),
    "choice": ("values",),
}
PLOT_KEYS = {"x", "y", "family", "error_map"}
ERROR_MAP_KEYS = {"x", "y", "output"}


class StudyError(ValueError):
    """A study file that cannot be run; the message starts with the offending key."""

    def __init__(self, key, message):
        super().__init__(f"{key}: {message}" if key else message)
        self.key = key


def fmu_interface(model_description):
    """The FMU's variables as plain data (what the workers and the validation need)."""
    variables = {}
    for v in model_description.modelVariables:
        items = None
        if v.declaredType is not None and getattr(v.declaredType, "items", None):
            items = {item.name: int(item.value) for item in v.declaredType.items}
        start = None
        if v.start is not None:
            start = {"Real": float, "String": str}.get(v.type, int)(v.start)
        variables[v.name] = {
            "vr": v.valueReference, "type": v.type, "causality": v.causality, "variability": v.variability,
            "start": start, "items": items, "declared_type": v.declaredType.name if v.declaredType else None,
        }
    return {"guid": model_description.guid, "model_identifier": model_description.coSimulation.modelIdentifier,
            "variables": variables}


def settable(interface):
    return [n for n, v in interface["variables"].items() if v["causality"] in ("input", "parameter")]


def output_names(interface):
    return [n for n, v in interface["variables"].items() if v["causality"] == "output"]


def unknown(key, name, known, what):
    close = difflib.get_close_matches(name, known, n=1)
    hint = f" (did you mean {close[0]}?)" if close else ""
    return StudyError(key, f"unknown {what} {name!r}{hint}")


def check_keys(key, table, allowed):
    if not isinstance(table, dict):
        raise StudyError(key, f"must be a table, not {type(table).__name__}")
    for name in table:
        if name not in allowed:
            where = f"{key}.{name}" if key else name
            close = difflib.get_close_matches(name, sorted(allowed), n=1)
            hint = f" (did you mean {close[0]}?)" if close else f" (allowed: {', '.join(sorted(allowed))})"
            raise StudyError(where, f"unknown key{hint}")


def variable_value(key, name, value, interface):
    """A value for a settable variable: a number for Real/Integer, an item name (or its number)
    for an Enumeration, a string for a String; returns the value the FMU is given."""
    variable = interface["variables"][name]
    if variable["items"] is not None:
        if isinstance(value, str):
            if value not in variable["items"]:
                raise StudyError(key, f"{value!r} is not a {variable['declared_type']} "
                                      f"({', '.join(variable['items'])})")
            return variable["items"][value]
        if isinstance(value, int) and not isinstance(value, bool) and value in variable["items"].values():
            return value
        raise StudyError(key, f"must be one of {', '.join(variable['items'])}, not {value!r}")
    if variable["type"] == "String":
        if not isinstance(value, str):
            raise StudyError(key, f"must be a string (a file path or a built-in profile's name), not {value!r}")
        return value
    if variable["type"] == "Integer":
        if isinstance(value, bool) or not isinstance(value, int):
            raise StudyError(key, f"must be an integer, not {value!r}")
        return value
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise StudyError(key, f"must be a number, not {value!r}")
    return float(value)


def settable_name(key, name, interface):
    variables = interface["variables"]
    if name not in variables:
        raise unknown(key, name, settable(interface), "variable")
    if variables[name]["causality"] not in ("input", "parameter"):
        raise StudyError(key, f"{name} is an {variables[name]['causality']}, not an input or parameter")
    return name


def grid_axis(key, spec, name, interface):
    if isinstance(spec, list):
        if not spec:
            raise StudyError(key, "is an empty list")
        return [variable_value(f"{key}[{i}]", name, x, interface) for i, x in enumerate(spec)]
    if isinstance(spec, dict):
        check_keys(key, spec, {"linspace", "geomspace"})
        if len(spec) != 1:
            raise StudyError(key, "needs exactly one of linspace = [start, stop, n] or geomspace = [start, stop, n]")
        (kind, arguments), = spec.items()
        if (not isinstance(arguments, list) or len(arguments) != 3 or isinstance(arguments[2], bool)
                or not isinstance(arguments[2], int) or arguments[2] < 1
                or not all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in arguments[:2])):
            raise StudyError(f"{key}.{kind}", "must be [start, stop, n] with n a positive integer")
        if interface["variables"][name]["type"] != "Real":
            raise StudyError(f"{key}.{kind}", f"{name} is not Real: give its values as a list")
        if kind == "geomspace" and (arguments[0] == 0 or arguments[1] == 0 or (arguments[0] > 0) != (arguments[1] > 0)):
            raise StudyError(f"{key}.geomspace", "start and stop must be non-zero and of one sign")
        values = (np.linspace if kind == "linspace" else np.geomspace)(arguments[0], arguments[1], arguments[2])
        return [float(x) for x in values]
    raise StudyError(key, "must be a list of values or a table { linspace = [...] } / { geomspace = [...] }")


def distribution(key, spec, name, interface):
    if not isinstance(spec, dict):
        raise StudyError(key, "must be a table such as { distribution = \"normal\", mean = 0.3, std = 0.03 }")
    kind = spec.get("distribution")
    if kind not in DISTRIBUTIONS:
        raise StudyError(f"{key}.distribution", f"must be one of {', '.join(DISTRIBUTIONS)}, not {kind!r}")
    check_keys(key, spec, {"distribution", *DISTRIBUTIONS[kind]})
    for argument in DISTRIBUTIONS[kind]:
        if argument not in spec:
            raise StudyError(f"{key}.{argument}", f"missing (a {kind} distribution needs {', '.join(DISTRIBUTIONS[kind])})")
    if kind == "choice":
        if not isinstance(spec["values"], list) or not spec["values"]:
            raise StudyError(f"{key}.values", "must be a non-empty list")
        return {"distribution": kind,
                "values": [variable_value(f"{key}.values[{i}]", name, x, interface) for i, x in enumerate(spec["values"])]}
    if interface["variables"][name]["type"] != "Real":
        raise StudyError(key, f"{name} is not Real: draw it with distribution = \"choice\"")
    arguments = {}
    for argument in DISTRIBUTIONS[kind]:
        value = spec[argument]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise StudyError(f"{key}.{argument}", f"must be a finite number, not {value!r}")
        arguments[argument] = float(value)
    if kind in ("uniform", "loguniform") and not arguments["low"] < arguments["high"]:
        raise StudyError(f"{key}.high", "must be greater than low")
    if kind == "loguniform" and arguments["low"] <= 0:
        raise StudyError(f"{key}.low", "must be > 0 for a loguniform distribution")
    if kind in ("normal", "lognormal") and arguments[DISTRIBUTIONS[kind][1]] < 0:
        raise StudyError(f"{key}.{DISTRIBUTIONS[kind][1]}", "must be >= 0")
    return {"distribution": kind, **arguments}


def random_table(key, table, interface, inherited=None):
    """[random] (seed, samples, variables) or a case's override of it."""
    check_keys(key, table, {"seed", "samples", *interface["variables"]})
    result = dict(inherited or {"seed": None, "samples": None, "variables": {}})
    result["variables"] = dict(result["variables"])
    for name, spec in table.items():
        where = f"{key}.{name}"
        if name in ("seed", "samples"):
            if isinstance(spec, bool) or not isinstance(spec, int) or spec < (0 if name == "seed" else 1):
                raise StudyError(where, f"must be an integer {'>= 0' if name == 'seed' else '>= 1'}, not {spec!r}")
            result[name] = spec
        else:
            settable_name(where, name, interface)
            result["variables"][name] = distribution(where, spec, name, interface)
    return result


def load(path, interface):
    """Reads and validates a study file; returns the normalised study (plain data, JSON-able)."""
    try:
        with open(path, "rb") as file:
            raw = tomllib.load(file)
    except tomllib.TOMLDecodeError as error:
        raise StudyError("", f"not valid TOML: {error}") from None
    return parse(raw, interface, default_name=pathlib.Path(path).stem)


def parse(raw, interface, default_name="study"):
    check_keys("", raw, TOP_LEVEL)
    variables = interface["variables"]
    model_items = variables[MODEL_PARAMETER]["items"]
    study = {"name": raw.get("name", default_name), "description": raw.get("description", "")}
    for key in ("name", "description"):
        if not isinstance(study[key], str):
            raise StudyError(key, "must be a string")

    models = raw.get("models", [next(n for n, x in model_items.items() if x == variables[MODEL_PARAMETER]["start"])])
    if not isinstance(models, list) or not models:
        raise StudyError("models", f"must be a non-empty list of model names ({', '.join(model_items)})")
    for i, model in enumerate(models):
        if model not in model_items:
            raise StudyError(f"models[{i}]", f"{model!r} is not a {MODEL_PARAMETER} ({', '.join(model_items)})")
    if len(set(models)) != len(models):
        raise StudyError("models", "lists a model twice")
    study["models"] = models

    outputs = raw.get("outputs", output_names(interface))
    if not isinstance(outputs, list) or not outputs:
        raise StudyError("outputs", "must be a non-empty list of output names")
    for i, name in enumerate(outputs):
        if name not in variables:
            raise unknown(f"outputs[{i}]", name, output_names(interface), "output")
        if variables[name]["causality"] != "output":
            raise StudyError(f"outputs[{i}]", f"{name} is an {variables[name]['causality']}, not an output")
    study["outputs"] = outputs

    for key, default, minimum in (("chunk_size", 50, 1), ("steps", 0, 0)):
        value = raw.get(key, default)
        if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
            raise StudyError(key, f"must be an integer >= {minimum}, not {value!r}")
        study[key] = value
    step_size = raw.get("step_size", 1e-3)
    if isinstance(step_size, bool) or not isinstance(step_size, (int, float)) or not step_size > 0:
        raise StudyError("step_size", f"must be a number > 0, not {step_size!r}")
    study["step_size"] = float(step_size)

    reference = raw.get("reference_model", "exact")
    if reference not in model_items:
        raise StudyError("reference_model", f"{reference!r} is not a {MODEL_PARAMETER} ({', '.join(model_items)})")
    study["reference_model"] = reference

    def values_table(key, table, skip=()):
        check_keys(key, table, set(variables) | set(skip))
        result = {}
        for name, value in table.items():
            if name in skip:
                continue
            settable_name(f"{key}.{name}", name, interface)
            if name == MODEL_PARAMETER:
                raise StudyError(f"{key}.{name}", "set the model with the top-level key models")
            result[name] = variable_value(f"{key}.{name}", name, value, interface)
        return result

    study["fixed"] = values_table("fixed", raw.get("fixed", {}))

    grid = raw.get("grid", {})
    check_keys("grid", grid, set(variables))
    study["grid"] = {}
    for name, spec in grid.items():
        settable_name(f"grid.{name}", name, interface)
        if name == MODEL_PARAMETER:
            raise StudyError(f"grid.{name}", "vary the model with the top-level key models")
        if name in study["fixed"]:
            raise StudyError(f"grid.{name}", "is also set in [fixed]")
        study["grid"][name] = grid_axis(f"grid.{name}", spec, name, interface)

    study["random"] = random_table("random", raw.get("random", {}), interface)

    cases = raw.get("cases", [])
    if not isinstance(cases, list):
        raise StudyError("cases", "must be an array of tables ([[cases]])")
    study["cases"] = []
    for i, case in enumerate(cases):
        key = f"cases[{i}]"
        if not isinstance(case, dict) or not isinstance(case.get("name"), str):
            raise StudyError(f"{key}.name", "missing: every case needs a name")
        values = values_table(key, case, skip=("name", "random"))
        random = random_table(f"{key}.random", case.get("random", {}), interface, study["random"])
        for name in values:
            if name in study["grid"] or name in random["variables"]:
                raise StudyError(f"{key}.{name}", "is also varied by [grid] or [random]")
        study["cases"].append({"name": case["name"], "values": values, "random": random})
    if len({c["name"] for c in study["cases"]}) != len(study["cases"]):
        raise StudyError("cases", "two cases have the same name")

    for random, key in [(study["random"], "random")] + [(c["random"], f"cases[{i}].random") for i, c in enumerate(study["cases"])]:
        if random["variables"]:
            for field in ("seed", "samples"):
                if random[field] is None:
                    raise StudyError(f"{key}.{field}", "missing: random draws need a seed and a number of samples")
        for name in random["variables"]:
            if name in study["grid"] or name in study["fixed"]:
                raise StudyError(f"{key}.{name}", "is also set in [fixed] or varied in [grid]")

    study["plot"] = plot_table(raw.get("plot", {}), study, interface)
    return study


# Columns the plots may use besides the FMU's variables (computed by report.DERIVED from these).
DERIVED = {"a_over_b": ("semi_axis_a", "semi_axis_b"), "adhesion_coefficient": ("force_longitudinal", "force_lateral")}


def plot_table(table, study, interface):
    """[plot]: x (a variable), y (outputs), family (a variable or a list: one line per
    combination), error_map (x and y: grid axes; output). Defaults: the first grid axis over the
    second, the first output."""
    check_keys("plot", table, PLOT_KEYS)
    axes = list(study["grid"])
    outputs = study["outputs"]
    columns = set(interface["variables"]) | set(DERIVED)
    plot = {"x": table.get("x", axes[0] if axes else None), "y": table.get("y", outputs[:1]), "error_map": None}
    plot["family"] = table.get("family", [a for a in axes[1:2] if a != plot["x"]])
    for key in ("y", "family"):
        if isinstance(plot[key], str):
            plot[key] = [plot[key]]
        if not isinstance(plot[key], list):
            raise StudyError(f"plot.{key}", "must be a name or a list of names")
    for key, names in (("x", [plot["x"]] if plot["x"] is not None else []), ("family", plot["family"])):
        for name in names:
            if not isinstance(name, str) or name not in columns:
                raise unknown(f"plot.{key}", name, sorted(columns), "variable")
            if name in DERIVED and name != "a_over_b":
                raise StudyError(f"plot.{key}", f"{name} is an output, not an axis")
    for i, name in enumerate(plot["y"]):
        if name in DERIVED and name != "a_over_b":
            missing = [o for o in DERIVED[name] if o not in outputs]
            if missing:
                raise StudyError(f"plot.y[{i}]", f"{name} needs the outputs {', '.join(missing)}")
        elif name not in outputs:
            raise StudyError(f"plot.y[{i}]", f"{name!r} is not among the study's outputs")
    if "error_map" in table:
        spec = table["error_map"]
        check_keys("plot.error_map", spec, ERROR_MAP_KEYS)
        for key in sorted(ERROR_MAP_KEYS):
            if key not in spec:
                raise StudyError(f"plot.error_map.{key}", "missing")
        for key in ("x", "y"):
            varied = spec[key] in study["grid"] or (spec[key] == "a_over_b" and any(a in study["grid"] for a in DERIVED["a_over_b"]))
            if not varied:
                raise StudyError(f"plot.error_map.{key}", f"{spec[key]!r} is not a [grid] axis")
        if spec["output"] not in outputs:
            raise StudyError("plot.error_map.output", f"{spec['output']!r} is not among the study's outputs")
        plot["error_map"] = dict(spec)
    return plot


def draws(random, rng_seed_offset):
    """The seeded samples of a [random] table: a list of {variable: value}, the same for every
    grid point and model (common random numbers, so models and grid points compare fairly)."""
    if not random["variables"]:
        return [{}]
    rng = np.random.default_rng([random["seed"], rng_seed_offset])
    n = random["samples"]
    columns = {}
    for name in sorted(random["variables"]):
        d = random["variables"][name]
        kind = d["distribution"]
        if kind == "uniform":
            x = rng.uniform(d["low"], d["high"], n)
        elif kind == "loguniform":
            x = np.exp(rng.uniform(math.log(d["low"]), math.log(d["high"]), n))
        elif kind == "normal":
            x = rng.normal(d["mean"], d["std"], n)
        elif kind == "lognormal":
            x = rng.lognormal(d["mean"], d["sigma"], n)
        else:
            x = [d["values"][i] for i in rng.integers(0, len(d["values"]), n)]
        columns[name] = [v.item() if hasattr(v, "item") else v for v in x]
    return [{name: columns[name][k] for name in columns} for k in range(n)]


def scenes(study, interface):
    """Every scene in a fixed order: case × model × grid point × sample. Each scene is
    (labels, values): labels = {case, sample}, values = every variable the FMU is given."""
    model_items = interface["variables"][MODEL_PARAMETER]["items"]
    cases = study["cases"] or [{"name": "", "values": {}, "random": study["random"]}]
    grid_names = list(study["grid"])
    result = []
    for case_index, case in enumerate(cases):
        samples = draws(case["random"], case_index)
        for model in study["models"]:
            for point in itertools.product(*(study["grid"][n] for n in grid_names)):
                for sample_index, sample in enumerate(samples):
                    values = {**study["fixed"], **case["values"], MODEL_PARAMETER: model_items[model],
                              **dict(zip(grid_names, point)), **sample}
                    result.append(({"case": case["name"], "sample": sample_index}, values))
    return result


# What fixes the scenes, their chunks and the columns of a part; the name, description, reference
# model and plots do not (changing them re-uses the chunks).
KEYED = ("models", "outputs", "chunk_size", "steps", "step_size", "fixed", "grid", "random", "cases")


def study_key(study, fmu_bytes):
    """Names a study's chunks: what of the normalised study fixes its scenes and chunks, and the
    FMU's bytes; a re-run with the same key reuses the chunks already written."""
    digest = hashlib.sha256(json.dumps({k: study[k] for k in KEYED}, sort_keys=True).encode())
    digest.update(hashlib.sha256(fmu_bytes).digest())
    return digest.hexdigest()[:16]


@dataclasses.dataclass
class Study:
    path: pathlib.Path
    fmu_bytes: bytes
    interface: dict
    study: dict
    scenes: list
    key: str

    @property
    def chunks(self):
        size = self.study["chunk_size"]
        return [self.scenes[i:i + size] for i in range(0, len(self.scenes), size)]


def prepare(study_path, fmu_path):
    """Reads the FMU and the study file and validates the study against the FMU's variables."""
    fmu_bytes = pathlib.Path(fmu_path).read_bytes()
    interface = fmu_interface(read_model_description(str(fmu_path)))
    study = load(study_path, interface)
    return Study(pathlib.Path(study_path), fmu_bytes, interface, study, scenes(study, interface),
                 study_key(study, fmu_bytes))
