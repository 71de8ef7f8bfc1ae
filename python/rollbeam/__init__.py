"""rollbeam from Python: the scenes, runs and sweeps of the ``rollbeam`` command line, with
results as numpy arrays in memory.

Units are SI throughout (m, s, kg, N, rad); signs and names are those of ``history.csv`` and
``summary.yaml`` (README.md, "Outputs"): ``w`` is the vertical displacement, positive up; the
disk's ``omega`` is its angular velocity, positive counter-clockwise, so a disk rolling to the
right has ``omega < 0``; ``rn`` is the normal force of the track on the disk, positive when it
presses.

Everything is computed by the Rust core through ``rollbeam._native``; this module only shapes
the answers. A scene is its scene-file text plus the values set on it, so it pickles, and one
sweep case is the pure function :func:`sweep_case` of (scene, values): any
``concurrent.futures.Executor`` can run it.
"""

from __future__ import annotations

import csv
import io
import itertools
import json
import os
import re
from pathlib import Path
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np
import yaml

from . import _native

__all__ = [
    "Scene",
    "Result",
    "Modes",
    "Table",
    "SceneError",
    "SolverError",
    "run",
    "check",
    "static",
    "modes",
    "tradeoff",
    "sweep",
    "sweep_case",
    "MAX_CASES",
]

#: Most cases one sweep runs, as on the command line.
MAX_CASES = 100_000
MAX_SCENE_BYTES = 64 << 20


class SceneError(ValueError):
    """The scene (or an argument) is invalid: the command line's one sentence, with the
    dotted ``key`` and the ``line`` of the scene text where it could tell them (else None)."""

    def __init__(self, message: str):
        super().__init__(message)
        self.message = message
        line = re.search(r"\bline (\d+)\b", message)
        key = re.search(r"`([^`]+)`", message)
        self.line: Optional[int] = int(line.group(1)) if line else None
        self.key: Optional[str] = key.group(1) if key else None


class SolverError(RuntimeError):
    """The solver could not go on (the command line's exit status 2). A physical stop (the
    disk left the track, lost contact, would slip) is not an error: it is a result with its
    reason in ``result.summary["stopped"]["reason"]``."""


def _call(function, *args, **kwargs):
    """A native call, its errors as this module's exceptions."""
    try:
        return function(*args, **kwargs)
    except _native.SceneError as e:
        raise SceneError(str(e)) from None
    except _native.SolverError as e:
        raise SolverError(str(e)) from None


class _Loader(yaml.SafeLoader):
    """YAML 1.2 numbers (``1e-9``, ``1.0e+300``), as the core writes them; PyYAML's 1.1
    rules would read some as text."""


_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(
        r"^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?"
        r"|[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)"
        r"|\.[0-9_]+(?:[eE][-+]?[0-9]+)?"
        r"|[-+]?\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$"
    ),
    list("-+0123456789."),
)


def _yaml(text: str) -> Any:
    return yaml.load(text, Loader=_Loader)


def _array(raw: bytes) -> np.ndarray:
    return np.frombuffer(raw, dtype=np.float64).copy()


class Scene:
    """A scene: what a scene file holds, with the same keys and checks (SCENE-FORMAT).

    ``Scene(dict)`` takes the scene as nested dicts and lists; ``Scene.from_yaml`` a path or
    the text of a scene file. A scene the format refuses raises :class:`SceneError` with the
    command line's sentence. Scenes are immutable: :meth:`with_values` returns a changed copy.
    """

    def __init__(self, data: Mapping[str, Any]):
        if not isinstance(data, Mapping):
            raise SceneError(
                f"Scene() takes the scene as a dict (got {type(data).__name__}); "
                "use Scene.from_yaml for a file or its text"
            )
        try:
            # JSON is YAML: the scene reader checks it as it checks a file.
            text = json.dumps(data, indent=1, allow_nan=False)
        except (TypeError, ValueError) as e:
            raise SceneError(f"the scene dict cannot be read: {e}") from None
        except RecursionError:
            raise SceneError(
                "the scene dict is nested deeper than any scene is (Python's recursion limit)"
            ) from None
        # Messages name the dict's keys, not lines of the JSON text its author never saw.
        self._set(text, "scene dict", "scene", [], lined=False)

    @classmethod
    def from_yaml(cls, path_or_text: Union[str, os.PathLike]) -> "Scene":
        """A scene from a scene file's path, or from its text."""
        scene = cls.__new__(cls)
        text = str(path_or_text)
        # One line that names something on disk, or a scene file's name, is a path: a folder,
        # a device or a misspelt file name is refused as such, not parsed as a scene's text.
        named = "\n" not in text and (os.path.lexists(text) or text.endswith((".yaml", ".yml")))
        if isinstance(path_or_text, os.PathLike) or _native.is_file(text) or named:
            path = Path(path_or_text)
            try:
                if not path.exists():
                    raise OSError("no such file")
                if not path.is_file():
                    raise OSError("not a regular file")
                if path.stat().st_size > MAX_SCENE_BYTES:
                    raise OSError(f"larger than a scene file can be ({MAX_SCENE_BYTES} bytes)")
                text = path.read_text()
            except (OSError, UnicodeDecodeError) as e:
                raise SceneError(f"cannot read scene file {path}: {e}") from None
            scene._set(text, str(path), path.stem, [])
        else:
            scene._set(str(path_or_text), "scene", "scene", [])
        return scene

    def _set(
        self,
        text: str,
        source: str,
        stem: str,
        values: List[Tuple[str, Any]],
        lined: bool = True,
    ) -> None:
        self._text = text
        self._source = source
        self._stem = stem
        self._lined = lined
        self._values = values
        self.name: str = _call(_native.plan, self)

    def with_values(self, values: Mapping[str, Any]) -> "Scene":
        """A copy with numbers or names set at dotted keys (``{"disk.omega0": -50.0,
        "train.hslm": "A3"}``), checked as a scene file would be."""
        changed = Scene.__new__(Scene)
        changed._set(
            self._text,
            self._source,
            self._stem,
            self._values + [(str(k), _value(str(k), v)) for k, v in values.items()],
            self._lined,
        )
        return changed

    def to_yaml(self) -> str:
        """The scene as a scene file, values written in."""
        return _call(_native.to_yaml, self)

    @property
    def source(self) -> str:
        """The file the scene was read from, "scene" for text, or "scene dict"."""
        return self._source

    def __repr__(self) -> str:
        return f"Scene({self.name!r}, from {self._source}, {len(self._values)} values set)"


def _scene(scene: Any, function: str) -> "Scene":
    """The scene argument, checked: a dict or a path given where a Scene belongs is named."""
    if not isinstance(scene, Scene):
        raise SceneError(
            f"{function}() takes a rollbeam.Scene (got {type(scene).__name__}); "
            "make one with rollbeam.Scene(dict) or rollbeam.Scene.from_yaml(path)"
        )
    return scene


def _plain(v: Any) -> Any:
    """numpy scalars as Python numbers and names."""
    if isinstance(v, np.generic):
        return v.item()
    return v


def _bounded(key: str, values: Iterable[Any]) -> List[Any]:
    """The values of one swept key, taken no further than a sweep can run: a range of a
    billion or an endless generator is refused before it is made into a list."""
    taken = list(itertools.islice(iter(values), MAX_CASES + 1))
    if len(taken) > MAX_CASES:
        raise SceneError(f"`{key}` has more than {MAX_CASES} values; sweep fewer values")
    return [_plain(v) for v in np.asarray(taken).tolist()]


def _value(key: str, v: Any) -> Any:
    """A value set at `key`: a finite number or a name, else a SceneError naming the key."""
    v = _plain(v)
    if isinstance(v, str):
        return v
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise SceneError(f"`{key}` = {v!r} is neither a number nor a name")
    try:
        number = float(v)
    except OverflowError:
        raise SceneError(f"`{key}` = {v} is too large for a double") from None
    if number != number or number in (float("inf"), float("-inf")):
        raise SceneError(f"`{key}` = {v} is not a finite number")
    return v


class Result:
    """One run. ``summary``: the ``summary.yaml`` content; ``history``: column name ->
    array, the ``history.csv`` names (an empty cell is NaN); ``t``: the output times (s);
    ``shapes`` and ``envelope`` (beam scenes, else None)."""

    def __init__(self, native: Any):
        self._native = native
        self.summary: Dict[str, Any] = _yaml(native.summary_yaml())
        self.history: Dict[str, np.ndarray] = {
            name: _array(raw) for name, raw in native.history()
        }
        self.t: np.ndarray = self.history["t"]
        shapes = native.shapes()
        if shapes is None:
            self.shapes: Optional[Dict[str, np.ndarray]] = None
        else:
            x, t = _array(shapes[0]), _array(shapes[1])
            grid = (len(t), len(x))
            self.shapes = {
                "x": x,
                "t": t,
                "u": _array(shapes[2]).reshape(grid),
                "w": _array(shapes[3]).reshape(grid),
                "phi": _array(shapes[4]).reshape(grid),
            }
        envelope = native.envelope()
        self.envelope: Optional[Dict[str, np.ndarray]] = (
            None if envelope is None else {name: _array(raw) for name, raw in envelope}
        )

    @property
    def stopped(self) -> str:
        """Why the run ended: ``end``, or the physical stop (``contact-lost``, ``slip``,
        ``left-track``, …)."""
        return self.summary["stopped"]["reason"]

    def write(self, directory: Union[str, os.PathLike], figures: bool = True) -> None:
        """Write exactly what ``rollbeam run`` writes: summary.yaml, history.csv and, unless
        ``figures=False`` (``rollbeam run --no-figures``), the SVG figures."""
        _call(self._native.write, os.fspath(directory), bool(figures))


def run(
    scene: Scene,
    method: Optional[str] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
) -> Result:
    """Run a scene; ``method`` (dopri5, trbdf2, esdirk4, genalpha, exact-modal), ``rtol``
    and ``atol`` override the scene's as ``rollbeam run --method --rtol --atol`` do. Releases
    the GIL."""
    _scene(scene, "run")
    return Result(_call(_native.run, scene, method, rtol, atol))


def check(scene: Scene) -> str:
    """What ``rollbeam check`` prints: the model the scene builds, what was chosen and why."""
    _scene(scene, "check")
    return _call(_native.check, scene)


def static(scene: Scene) -> Dict[str, Any]:
    """Static equilibrium of a beam scene (``static.yaml``): probes' u, w (m), phi (rad),
    the supports' reactions fx, fy (N), mz (N m) on the beam in global axes."""
    _scene(scene, "static")
    return _yaml(_call(_native.static_yaml, scene))


class Modes:
    """Natural frequencies and mass-normalised mode shapes about the undeformed beam:
    ``frequencies_hz`` (n,), ``x`` (m, points,), ``u``, ``w`` (m), ``phi`` (rad), each
    (n, points)."""

    def __init__(self, raw: Sequence[bytes]):
        self.frequencies_hz = _array(raw[0])
        self.x = _array(raw[1])
        grid = (len(self.frequencies_hz), len(self.x))
        self.u = _array(raw[2]).reshape(grid)
        self.w = _array(raw[3]).reshape(grid)
        self.phi = _array(raw[4]).reshape(grid)

    def __repr__(self) -> str:
        return f"Modes({np.array2string(self.frequencies_hz, precision=4)} Hz)"


def modes(scene: Scene, count: Optional[int] = None, samples: int = 200) -> Modes:
    """The lowest ``count`` modes (default 6, or as many as a modal beam keeps or the mesh
    holds), the shapes at ``samples + 1`` evenly spaced points."""
    _scene(scene, "modes")
    for name, n in (("count", count), ("samples", samples)):
        if n is not None and (isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1):
            raise SceneError(f"`{name}` = {n!r} must be a whole number of at least 1")
    return Modes(_call(_native.modes, scene, count, samples))


class Table(dict):
    """Columns by name: one per swept key (named by the key) and one per ``sweep.csv``
    column; numbers as float arrays (an empty cell is NaN), text as arrays of str."""

    def to_pandas(self):
        """The table as a pandas DataFrame (pandas must be installed)."""
        import pandas

        return pandas.DataFrame(dict(self))

    @property
    def rows(self) -> int:
        return len(next(iter(self.values()))) if self else 0


def _table(text: str) -> Table:
    reader = csv.reader(io.StringIO(text))
    head = next(reader)
    body = list(reader)
    table = Table()
    for k, name in enumerate(head):
        cells = [row[k] if k < len(row) else "" for row in body]
        try:
            table[name] = np.array([float(c) if c else np.nan for c in cells])
        except ValueError:
            table[name] = np.array(cells, dtype=str)
    return table


def tradeoff(
    scene: Scene,
    out: Union[str, os.PathLike, None] = None,
    methods: Iterable[str] = (),
    rtols: Iterable[float] = (),
    elements: Iterable[int] = (),
    orders: Iterable[int] = (),
    models: Iterable[str] = (),
    max_steps: Optional[int] = None,
) -> Tuple[Table, List[str]]:
    """Work–precision of a scene as ``rollbeam tradeoff`` runs it, into ``out`` (default
    ``out/<name>-tradeoff``): the table of ``tradeoff.csv`` and the lines the command prints
    (the reference's origin and the cheapest settings for 1e-2, 1e-4 and 1e-6). A scene read
    from a file uses the reference stored beside it where one serves."""
    _scene(scene, "tradeoff")
    directory = Path(out) if out is not None else Path("out") / f"{scene.name}-tradeoff"
    file = scene.source if _native.is_file(scene.source) else None
    lines = _call(
        _native.tradeoff,
        scene,
        os.fspath(directory),
        file,
        list(methods),
        [float(r) for r in rtols],
        [int(n) for n in elements],
        [int(k) for k in orders],
        list(models),
        max_steps,
    )
    return _table((directory / "tradeoff.csv").read_text()), lines


def sweep_case(
    scene: Scene,
    keys: Sequence[str],
    values: Sequence[Any],
    method: Optional[str] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
) -> str:
    """One case of a sweep, the values set at the keys: its record (the text a planned
    sweep's ``done/<id>.yaml`` holds). A pure, picklable function of its arguments, for
    executors; a case that cannot run records why."""
    _scene(scene, "sweep_case")
    keys, values = list(keys), list(values)
    if len(keys) != len(values):
        raise SceneError(
            f"{len(keys)} keys ({', '.join(map(str, keys))}) and {len(values)} values: give one value per key"
        )
    values = [_value(str(k), v) for k, v in zip(keys, values)]
    return _call(_native.run_case, scene, keys, values, method, rtol, atol)


def sweep(
    scene: Scene,
    values: Mapping[str, Iterable[Any]],
    executor: Any = None,
    method: Optional[str] = None,
    rtol: Optional[float] = None,
    atol: Optional[float] = None,
) -> Table:
    """The scene over the grid of every combination of ``values`` (dotted key -> numbers or
    names), the last key varying fastest. ``executor=None`` runs the cases on this machine's
    cores (GIL released); otherwise each case is :func:`sweep_case` submitted to the given
    ``concurrent.futures.Executor`` (a process pool, ``dask.distributed.Client.get_executor()``,
    a Slurm executor). Either way the table is the one ``rollbeam sweep`` writes as
    ``sweep.csv``, with one row per case in grid order."""
    _scene(scene, "sweep")
    if not values:
        raise SceneError("sweep needs at least one key with values")
    keys = [str(k) for k in values]
    lists = [_bounded(key, vs) for key, vs in zip(keys, values.values())]
    count = 1
    for key, vs in zip(keys, lists):
        if not vs:
            raise SceneError(f"`{key}` has no values to sweep")
        count *= len(vs)
        if count > MAX_CASES:
            raise SceneError(f"the values make more than {MAX_CASES} cases; sweep fewer values")
    # A key the scene cannot hold or a value it cannot take is the sweep's error, as on the
    # command line, not every case's.
    _call(_native.settable, scene, keys, lists)
    cases = [list(c) for c in itertools.product(*lists)]
    if executor is None:
        text = _call(_native.sweep_cases, scene, keys, cases, method, rtol, atol)
    else:
        futures = [
            executor.submit(sweep_case, scene, keys, case, method, rtol, atol) for case in cases
        ]
        text = _call(_native.merge, keys, [f.result() for f in futures])
    return _table(text)
