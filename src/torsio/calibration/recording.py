"""A rig recording: top-drive speed and surface torque against time, read from a CSV file.

The header names the columns; ``time``, a top-drive speed and the surface torque are
required, a downhole bit speed is optional, other columns are read past. A column name
may carry its unit in brackets or parentheses; without one, the defaults apply:

==================  =========================  ===============================================
column              default unit               units accepted in brackets
==================  =========================  ===============================================
``time``            s                          s, ms, min
``top_rpm``         rpm                        (a name ending in ``_rpm`` is in rpm)
``top_speed``       rad/s                      rpm, rad/s, deg/s
``surface_torque``  N m                        N*m (N.m, Nm), kN*m (kN.m, kNm), ft*lbf (ft.lbf,
                                               lbf*ft), kft*lbf (kft.lbf, klbf*ft)
``bit_rpm``         rpm (optional)             as ``top_rpm``; or ``bit_speed`` as ``top_speed``
==================  =========================  ===============================================

e.g. ``time[s],top_speed[rad/s],surface_torque[kN*m]``. Blank lines and lines starting
with ``#`` are skipped. Checks, each an error (:class:`~torsio.errors.ConfigError`) naming
the file and the line: a missing column, a field that is not a finite number, a time that
does not increase, an unknown unit. Warnings naming the line: a gap (a time step more
than 5 times the median step) and spikes (:mod:`torsio.calibration.spikes`: counted, the
first few named by their line).

Examples
--------
>>> import pathlib, tempfile
>>> with tempfile.TemporaryDirectory() as folder:
...     path = pathlib.Path(folder) / "rig.csv"
...     _ = path.write_text("time,top_rpm,surface_torque\\n0,0,0\\n1,30,5000\\n2,60,8000\\n")
...     record = read_recording(path)
>>> record
Recording(rig.csv: 3 samples over 2 s, top speed up to 60 rpm, surface torque up to 8000 N m)
>>> round(float(record.top_speed[-1]), 6)  # rad/s
6.283185
>>> with tempfile.TemporaryDirectory() as folder:
...     path = pathlib.Path(folder) / "bad.csv"
...     _ = path.write_text("time,top_rpm,surface_torque\\n0,0,0\\n0,30,5000\\n")
...     read_recording(path)
Traceback (most recent call last):
...
torsio.errors.ConfigError: recording: bad.csv, line 3: time 0 s does not increase ...
"""

from __future__ import annotations

import csv
import math
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

import attrs
import numpy as np

from torsio.calibration.spikes import SIGMAS, WINDOW, torque_spikes, without_spikes
from torsio.csv_rows import csv_rows, header_cell
from torsio.errors import ConfigError
from torsio.model.arrays import read_only
from torsio.output_files import atomic_output

if TYPE_CHECKING:
    from torsio.analysis.transient_results import TransientResults

__all__ = ["Recording", "read_recording"]

RPM = math.pi / 30.0

COLUMN_UNITS: dict[str, dict[str, float]] = {
    "time": {"s": 1.0, "ms": 1e-3, "min": 60.0},
    "speed": {"rpm": RPM, "rad/s": 1.0, "deg/s": math.pi / 180.0},
    "torque": {
        **dict.fromkeys(("n*m", "n.m", "nm", "n m"), 1.0),
        **dict.fromkeys(("kn*m", "kn.m", "knm", "kn m"), 1e3),
        **dict.fromkeys(("ft*lbf", "ft.lbf", "lbf*ft", "ft lbf"), 1.3558179483314004),
        **dict.fromkeys(("kft*lbf", "kft.lbf", "klbf*ft", "kft lbf"), 1.3558179483314004e3),
    },
}
"""Factors to SI of the units a column may name in brackets, by the column's dimension."""

COLUMNS: dict[str, tuple[str, str]] = {
    "time": ("time", "s"),
    "top_rpm": ("speed", "rpm"),
    "top_speed": ("speed", "rad/s"),
    "surface_torque": ("torque", "n*m"),
    "bit_rpm": ("speed", "rpm"),
    "bit_speed": ("speed", "rad/s"),
}
"""Column names read, with their dimension and default unit."""

GAP_FACTOR = 5.0
NAMED = 3
"""Gaps or spikes named by their line in a warning (the others counted)."""

MAX_BYTES = 20e6
"""The largest recording file read [bytes], checked before it is read: a line of a
recording takes about 40 bytes in the file and, read, about 600 bytes of memory, and each
run of a fit simulates the whole record (a 60 s start-up takes about 0.06 s of stepping)."""


def _area(time: np.ndarray, speed: np.ndarray, at: np.ndarray) -> np.ndarray:
    """The exact integral from time[0] to ``at`` of the speed, linear between samples."""
    step = np.diff(time)
    cumulative = np.concatenate([[0.0], np.cumsum(0.5 * (speed[1:] + speed[:-1]) * step)])
    k = np.clip(np.searchsorted(time, at, side="right") - 1, 0, time.size - 2)
    x = at - time[k]
    slope = (speed[k + 1] - speed[k]) / step[k]
    return cumulative[k] + speed[k] * x + 0.5 * slope * x * x


@attrs.frozen(eq=False, repr=False)
class Recording:
    """Top-drive speed and surface torque against time, in SI units.

    Attributes
    ----------
    time : ndarray
        Sample times [s], increasing.
    top_speed : ndarray
        Top-drive speed [rad/s].
    surface_torque : ndarray
        Torque in the string at the top [N m] (what a torque sub measures).
    bit_speed : ndarray or None
        Bit speed from a downhole tool [rad/s], if recorded.
    name : str
        Where it came from (the file's name), for messages and reports.
    """

    time: np.ndarray = attrs.field(converter=read_only)
    top_speed: np.ndarray = attrs.field(converter=read_only)
    surface_torque: np.ndarray = attrs.field(converter=read_only)
    bit_speed: np.ndarray | None = attrs.field(
        default=None, converter=attrs.converters.optional(read_only)
    )
    name: str = "recording"

    def __attrs_post_init__(self) -> None:
        n = self.time.size
        arrays = [self.top_speed, self.surface_torque]
        arrays += [] if self.bit_speed is None else [self.bit_speed]
        if n < 2 or any(a.shape != (n,) for a in arrays):
            raise ConfigError(
                "recording", f"{self.name}: expected at least 2 samples, every column as long"
            )
        if not np.all(np.diff(self.time) > 0.0):
            raise ConfigError("recording", f"{self.name}: times must increase")
        if not all(np.all(np.isfinite(a)) for a in [self.time, *arrays]):
            raise ConfigError("recording", f"{self.name}: every value must be finite")

    def __repr__(self) -> str:
        return (
            f"Recording({self.name}: {self.time.size} samples over "
            f"{self.duration:g} s, top speed up to {self.top_speed.max() / RPM:.4g} rpm, "
            f"surface torque up to {self.surface_torque.max():.4g} N m)"
        )

    @classmethod
    def from_transient(
        cls,
        results: TransientResults,
        *,
        torque_noise: float = 0.0,
        speed_noise: float = 0.0,
        seed: int = 0,
        bit_speed: bool = False,
        name: str = "recording",
    ) -> Recording:
        """What a rig would have recorded of a run: its time, top-drive speed and surface
        torque (and, with ``bit_speed``, a downhole tool's bit speed).

        ``torque_noise`` and ``speed_noise`` are relative standard deviations of Gaussian
        noise, drawn sample by sample from ``numpy.random.default_rng(seed)`` (the speed's
        first, then the torque's, then the bit speed's, which takes ``speed_noise``):
        a recorded value is the run's value times (1 + noise × a standard normal draw).

        Examples
        --------
        >>> from torsio.analysis.transient import simulate
        >>> from torsio.examples import builtin_config
        >>> run = simulate(builtin_config().system(strategy="A").at(wob=175e3, rpm=100))
        >>> clean = Recording.from_transient(run, name="strategy A")
        >>> bool((clean.surface_torque == run.surface_torque).all())
        True
        >>> noisy = Recording.from_transient(run, torque_noise=0.02, seed=1, bit_speed=True)
        >>> spread = noisy.surface_torque / run.surface_torque - 1.0
        >>> 0.015 < float(spread[run.surface_torque != 0].std()) < 0.025
        True
        >>> noisy.bit_speed is not None
        True
        """
        rng = np.random.default_rng(seed)
        n = results.time.size
        top_speed = results.top_speed * (1.0 + speed_noise * rng.normal(size=n))
        torque = results.surface_torque * (1.0 + torque_noise * rng.normal(size=n))
        bit = None
        if bit_speed:
            bit = results.bit_speed * (1.0 + speed_noise * rng.normal(size=n))
        return cls(
            time=results.time,
            top_speed=top_speed,
            surface_torque=torque,
            bit_speed=bit,
            name=name,
        )

    def spikes(self) -> np.ndarray:
        """Indices of the samples whose surface torque is a spike
        (:func:`~torsio.calibration.spikes.torque_spikes`)."""
        return torque_spikes(self.surface_torque)

    def without_spikes(self) -> Recording:
        """The recording with each spike of the surface torque replaced by the record
        linear between its neighbours that are not spikes."""
        torque = without_spikes(self.time, self.surface_torque, self.spikes())
        return attrs.evolve(self, surface_torque=torque)

    @property
    def duration(self) -> float:
        """Time from the first sample to the last [s]."""
        return float(self.time[-1] - self.time[0])

    def speed_table(self, smoothing: float = 0.0) -> np.ndarray:
        """The top-drive speed as a set-speed table, rows (time from the first sample [s],
        speed [rad/s]): what a top held at the recorded speed follows.

        ``smoothing`` [s]: each speed is the mean of the record (linear between samples)
        over a window that long centred on its sample (cut at the record's ends), which
        keeps a ramp and a constant speed and takes out sample-to-sample noise; 0: the
        speeds as recorded.

        >>> record = Recording(time=[0.0, 1.0, 2.0, 3.0], top_speed=[0.0, 1.0, 2.0, 3.0],
        ...                    surface_torque=[0.0, 0.0, 0.0, 0.0])
        >>> record.speed_table(smoothing=1.0)[1].tolist()   # a ramp, inside: unchanged
        [0.25, 1.0, 2.0, 2.75]
        """
        time = self.time - self.time[0]
        speed = np.asarray(self.top_speed, dtype=float)
        if not (math.isfinite(smoothing) and smoothing >= 0.0):
            raise ConfigError("speed_smoothing", f"expected a window >= 0 in s, got {smoothing!r}")
        if smoothing > 0.0 and time.size > 1:
            low = np.maximum(time - 0.5 * smoothing, time[0])
            high = np.minimum(time + 0.5 * smoothing, time[-1])
            speed = (_area(time, speed, high) - _area(time, speed, low)) / (high - low)
        return np.vstack([time, speed])

    def save(self, path: str | Path) -> None:
        """Write the recording as CSV with the header ``time,top_rpm,surface_torque``
        (and ``bit_rpm`` if recorded), in s, rpm and N m."""
        columns = [self.time, self.top_speed / RPM, self.surface_torque]
        header = ["time", "top_rpm", "surface_torque"]
        if self.bit_speed is not None:
            columns.append(self.bit_speed / RPM)
            header.append("bit_rpm")
        with atomic_output(path) as stream:  # whole or not at all (OutputError)
            writer = csv.writer(stream)
            writer.writerow(header)
            writer.writerows(zip(*(c.tolist() for c in columns), strict=True))


def _columns(header: list[str], name: str, line: int) -> dict[str, tuple[int, float]]:
    """Column index and factor to SI of each column read, by its canonical name."""
    found: dict[str, tuple[int, float]] = {}
    for index, cell in enumerate(header):
        column, given_unit = header_cell(cell)
        if column not in COLUMNS:
            continue
        dimension, default = COLUMNS[column]
        unit = (given_unit or default).lower()
        units = COLUMN_UNITS[dimension]
        if unit not in units:
            raise ConfigError(
                "recording",
                f"{name}, line {line}: column {cell.strip()!r}: unknown unit {unit!r}; "
                f"expected one of {', '.join(sorted(units))}",
            )
        kind = column.split("_")[0] + ("_speed" if dimension == "speed" else "")
        key = {"time": "time", "surface": "surface_torque"}.get(kind, kind)
        if key in found:
            raise ConfigError("recording", f"{name}, line {line}: {key} is given twice")
        found[key] = (index, units[unit])
    missing = [k for k in ("time", "top_speed", "surface_torque") if k not in found]
    if missing:
        raise ConfigError(
            "recording",
            f"{name}, line {line}: the header {','.join(header)!r} has no column for "
            f"{', '.join(missing)}; expected time,top_rpm,surface_torque (optional bit_rpm)",
        )
    return found


def _value(cell: str, column: str, name: str, line: int) -> float:
    try:
        value = float(cell)
    except ValueError:
        value = math.nan
        text = cell.strip()
        if text.lower() not in ("nan", "inf", "-inf"):
            hint = ""
            if "," in text or "'" in text or " " in text:
                hint = " (a thousands separator? write the number without it)"
            elif any(c.isalpha() for c in text):
                hint = " (a letter in a number: O typed for 0?)"
            raise ConfigError(
                "recording",
                f"{name}, line {line}: column {column}: {cell!r} is not a number{hint}",
            ) from None
    if not math.isfinite(value):
        raise ConfigError(
            "recording",
            f"{name}, line {line}: column {column}: {cell.strip()!r} is not a finite number "
            "(remove or fill the sample)",
        )
    return value


def _warn_at(
    name: str,
    lines: list[int],
    samples: np.ndarray,
    what: str,
    message: Callable[[int], str],
    after: str = "",
) -> None:
    """One warning for ``samples`` (indices): their count, the line of each of the first
    :data:`NAMED`, then ``after``."""
    if samples.size == 0:
        return
    named = "; ".join(f"line {lines[i]}: {message(i)}" for i in samples[:NAMED])
    more = f" (the first {NAMED} named)" if samples.size > NAMED else ""
    count = f"{samples.size} {what}{'s' if samples.size > 1 else ''} in all{more}"
    warnings.warn(f"{name}: {count}: {named}{after}", UserWarning, stacklevel=4)


def _check_times(time: np.ndarray, lines: list[int], name: str) -> None:
    steps = np.diff(time)
    bad = np.flatnonzero(steps <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        raise ConfigError(
            "recording",
            f"{name}, line {lines[i]}: time {time[i]:g} s does not increase "
            f"(the line before: {time[i - 1]:g} s)",
        )
    median = float(np.median(steps))
    _warn_at(
        name,
        lines,
        np.flatnonzero(steps > GAP_FACTOR * median) + 1,
        "gap",
        lambda i: (
            f"a gap of {steps[i - 1]:g} s in the time (the median step is {median:g} s); "
            "the model follows the speed linearly across it"
        ),
    )


def _check_spikes(torque: np.ndarray, lines: list[int], name: str) -> None:
    _warn_at(
        name,
        lines,
        torque_spikes(torque),
        "surface-torque spike",
        lambda i: f"{torque[i]:g} N m",
        f" (more than {SIGMAS:g} times the record's scale from the median of its {WINDOW} "
        "neighbours; a fit replaces each by the record linear between its neighbours)",
    )


def read_recording(path: str | Path) -> Recording:
    """The :class:`Recording` in the CSV file ``path`` (columns and units: module docs).

    Raises
    ------
    ConfigError
        The file cannot be read or is larger than :data:`MAX_BYTES`, its header lacks a
        column or names an unknown unit, a line has more or fewer fields than the header,
        a value is not a finite number or a time does not increase; the message names the
        file and the line (and the column).
    """
    path = Path(path)
    name = path.name
    try:
        size = path.stat().st_size
    except OSError:
        size = 0  # csv_rows says why it cannot be read
    if size > MAX_BYTES:
        raise ConfigError(
            "recording",
            f"{name}: {size / 1e6:.4g} MB, more than the {MAX_BYTES / 1e6:g} MB a recording "
            "may take (about 500,000 samples: 1.4 h at 100 samples per second); cut it to "
            "the start-ups, or resample it",
        )
    rows = csv_rows(path, "recording", "recording", "time,top_rpm,surface_torque")
    header_line, header = rows[0]
    columns = _columns(header, name, header_line)
    values: dict[str, list[float]] = {key: [] for key in columns}
    lines = []
    for number, row in rows[1:]:
        if len(row) != len(header):
            hint = ""
            if len(row) > len(header):
                hint = " (a thousands separator or a decimal comma in a comma-separated file?)"
            raise ConfigError(
                "recording",
                f"{name}, line {number}: {len(row)} fields, expected {len(header)} as the "
                f"header {','.join(header)!r}{hint}",
            )
        for key, (index, factor) in columns.items():
            values[key].append(_value(row[index], header[index].strip(), name, number) * factor)
        lines.append(number)
    if len(lines) < 2:
        raise ConfigError("recording", f"{name}: expected at least 2 samples after the header")
    time = np.asarray(values["time"])
    _check_times(time, lines, name)
    torque = np.asarray(values["surface_torque"])
    _check_spikes(torque, lines, name)
    bit = values.get("bit_speed")
    return Recording(
        time=time,
        top_speed=values["top_speed"],
        surface_torque=torque,
        bit_speed=None if bit is None else bit,
        name=name,
    )
