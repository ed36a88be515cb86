"""Compiled bit-rock law kernels: the contract between a law and the compiled batch engine.

A bit-rock law MAY provide a method ``kernel()`` returning
``(torque_function, slope_function, parameters)``:

* ``torque_function(parameters, speed, wob, radius)`` and
  ``slope_function(parameters, speed, wob, radius)`` are numba functions compiled
  with the explicit signature :data:`LAW_SIGNATURE`,
  ``float64(float64[::1], float64, float64, float64)``: the law's parameter array,
  the bit speed [rad/s], the weight on bit [N] and the bit radius [m]; they return
  the torque on bit [N m] and its derivative with respect to the speed [N m s/rad];
* ``parameters`` is a contiguous float64 array (the law's parameters in the rad/s
  reading).

The batch kernel takes the two functions as first-class function arguments
(``numba.types.FunctionType``) in an explicit signature, so it is compiled and
cached once for every law; a law only compiles its own two small functions.
:func:`compile_law_function` compiles a plain Python function with that
signature (lazily, cached on disk). Written with numpy ufuncs (``np.tanh``,
``np.exp``, ``np.abs``), the same function also serves the law's vectorized
``torque`` over arrays, so the formula is written once.

A law without ``kernel()`` gets one from its Python ``torque`` (and ``slope``, or the
central difference of :func:`torsio.physics.law_slope.central_difference`) where numba can
compile them (:func:`python_law_kernel`): the law's numeric attributes are handed to the
compiled method as a named tuple in place of ``self``. Where it cannot, single runs use
scipy and maps the numpy engine, and say so.

Examples
--------
>>> from torsio.physics.laws import TuckerWang
>>> law = TuckerWang(a0=0.221, a1=0.2, a2=0.89, a3=0.06, speed_unit="rpm")
>>> kernel = law_kernel(law)
>>> kernel is not None and kernel.parameters.tolist() == [law.a0, law.a1, law.a2, law.a3]
True
>>> compiled = kernel.torque(kernel.parameters, 10.0, 100e3, 0.108)
>>> abs(compiled - float(law.torque(10.0, 100e3, 0.108)))
0.0
"""

from __future__ import annotations

from collections.abc import Callable
from functools import cache
from typing import Any

import attrs
import numpy as np

from torsio.errors import ConfigError

__all__ = [
    "LAW_SIGNATURE",
    "LawKernel",
    "compile_law_function",
    "law_kernel",
    "law_type",
    "python_law_kernel",
]

LAW_SIGNATURE = "float64(float64[::1], float64, float64, float64)"
"""numba signature of a law's torque and slope functions: (parameters, speed, wob, radius)."""


def law_type() -> Any:
    """The numba type of a law function (``FunctionType(LAW_SIGNATURE)``); needs numba."""
    from numba import types

    f8 = types.float64
    return types.FunctionType(f8(f8[::1], f8, f8, f8))


@cache
def compile_law_function(function: Callable[..., float]) -> Any:
    """``function`` compiled by numba with :data:`LAW_SIGNATURE` (cached on disk).

    Compiles once per process (the on-disk cache makes later processes load it);
    a ConfigError names the function if numba cannot compile it.
    """
    import numba

    from torsio.kernel_cache import watch_compiles

    watch_compiles()
    try:
        try:
            return numba.njit(LAW_SIGNATURE, cache=True)(function)
        except RuntimeError as exc:  # no file to cache next to (exec'd code): compile only
            if "no locator" not in str(exc):
                raise
            return numba.njit(LAW_SIGNATURE)(function)
    except Exception as exc:  # numba's typing errors are long; say which function failed
        name = getattr(function, "__qualname__", repr(function))
        raise ConfigError(
            "bit_rock.law",
            f"the law function {name} does not compile with numba "
            f"({LAW_SIGNATURE}): {type(exc).__name__}: {str(exc).splitlines()[0]}",
        ) from None


@attrs.frozen
class LawKernel:
    """A law's compiled torque and slope functions with their parameter array.

    Attributes
    ----------
    torque, slope : numba function
        (parameters, speed [rad/s], wob [N], radius [m]) -> N m and N m s/rad.
    parameters : ndarray
        Contiguous float64 parameters of the law.
    """

    torque: Any
    slope: Any
    parameters: np.ndarray


def law_kernel(law: Any) -> LawKernel | None:
    """The compiled kernel a law provides through ``kernel()``, or None if it has none.

    A ``kernel()`` that returns something else than ``(torque, slope, parameters)``
    with numba functions of :data:`LAW_SIGNATURE` is a ConfigError naming the law.
    """
    method = getattr(law, "kernel", None)
    if method is None:
        return None
    name = getattr(law, "name", type(law).__name__)
    provided = method()
    if provided is None:
        return None
    if not (isinstance(provided, tuple) and len(provided) == 3):
        raise ConfigError(
            "bit_rock.law",
            f"law {name!r}: kernel() must return (torque_function, slope_function, "
            f"parameters), got {provided!r}",
        )
    torque, slope, parameters = provided
    for label, function in (("torque", torque), ("slope", slope)):
        signatures = getattr(function, "signatures", None)
        if signatures is None or len(signatures) != 1:
            raise ConfigError(
                "bit_rock.law",
                f"law {name!r}: the kernel's {label} function must be compiled by numba with "
                f"the one signature {LAW_SIGNATURE} (torsio.solvers.law_kernels."
                f"compile_law_function does it), got {function!r}",
            )
    array = np.ascontiguousarray(parameters, dtype=float).ravel()
    if array.size == 0:
        array = np.zeros(1)  # numba needs an array; a law without parameters ignores it
    return LawKernel(torque, slope, array)


CHECK_SPEEDS = (-20.0, -1.0, -0.05, 0.0, 1e-3, 0.05, 0.5, 2.0, 7.0, 30.0)
"""Bit speeds [rad/s] at which a kernel compiled from Python is checked against the law."""


def python_law_kernel(law: Any, wob: float = 1e5, radius: float = 0.1) -> LawKernel:
    """A kernel compiled by numba from a law's own Python ``torque`` and ``slope``.

    The methods are compiled with ``self`` replaced by a named tuple of the law's numeric
    attributes; without ``slope``, the slope is the compiled central difference of the
    torque (:func:`torsio.physics.law_slope.central_difference`). The compiled torque and slope
    must equal the law's at :data:`CHECK_SPEEDS` (at ``wob`` [N], ``radius`` [m]) to 1e-12
    relative, or the kernel is refused. A ConfigError says why it cannot be compiled.
    """
    import collections

    import numba

    from torsio.physics.law_slope import SLOPE_STEP, bit_slope, central_difference

    name = getattr(law, "name", type(law).__name__)
    values = {
        key: float(value)
        for key, value in _attributes(law).items()
        if key.isidentifier()
        and not key.startswith("_")
        and isinstance(value, int | float | np.integer | np.floating)
        and not isinstance(value, bool)
    }
    key = (type(law), tuple(values.items()))
    if key in _COMPILED:
        return _COMPILED[key]
    this = collections.namedtuple("LawParameters", list(values))(**values)

    def method(label: str) -> Any:
        function = getattr(type(law), label, None)
        if function is None or isinstance(function, staticmethod):
            return None
        inner = numba.njit(function)

        def bound(speed: float, wob: float, radius: float) -> float:
            return inner(this, speed, wob, radius)

        return numba.njit(bound)

    try:
        torque3 = method("torque")
        if torque3 is None:
            raise TypeError("no torque method")
        slope3 = method("slope") if hasattr(law, "slope") else None
        difference = numba.njit(central_difference)

        def torque(p: np.ndarray, speed: float, wob: float, radius: float) -> float:
            return torque3(speed, wob, radius)

        if slope3 is not None:

            def slope(p: np.ndarray, speed: float, wob: float, radius: float) -> float:
                return slope3(speed, wob, radius)
        else:

            def slope(p: np.ndarray, speed: float, wob: float, radius: float) -> float:
                return difference(torque3, speed, wob, radius)

        kernel = LawKernel(
            numba.njit(LAW_SIGNATURE)(torque), numba.njit(LAW_SIGNATURE)(slope), np.zeros(1)
        )
        speeds = np.array(CHECK_SPEEDS)
        compiled = [
            np.array([f(kernel.parameters, w, wob, radius) for w in speeds])
            for f in (kernel.torque, kernel.slope)
        ]
    except Exception as exc:  # numba's typing errors are long: the first line says enough
        raise ConfigError(
            "bit_rock.law",
            f"law {name!r} has no kernel() and numba cannot compile its Python torque/slope "
            f"({type(exc).__name__}: {str(exc).splitlines()[0] if str(exc) else exc!r})",
        ) from None
    with np.errstate(all="ignore"):
        python = [
            np.broadcast_to(np.asarray(law.torque(speeds, wob, radius), dtype=float), speeds.shape),
            np.broadcast_to(bit_slope(law, speeds, wob, radius), speeds.shape),
        ]
    # a slope by central difference carries the torque's round-off divided by the step: the
    # torques agreeing to 1e-12, their difference quotients agree to 1e-12 |T| / step
    torque_scale = float(np.max(np.abs(python[0]))) + 1e-300
    steps = SLOPE_STEP * np.maximum(1.0, np.abs(speeds))  # central_difference's
    quotient = 0.0 if slope3 is not None else 1e-12 * torque_scale / steps
    for label, ours, theirs, extra in zip(
        ("torque", "slope"), compiled, python, (0.0, quotient), strict=True
    ):
        scale = np.maximum(np.abs(theirs), np.max(np.abs(theirs)) * 1e-9 + 1e-300)
        if not np.all(np.abs(ours - theirs) <= 1e-12 * scale + extra):
            raise ConfigError(
                "bit_rock.law",
                f"law {name!r}: its {label} compiled by numba differs from its Python {label} "
                f"(at bit speeds {list(CHECK_SPEEDS)} rad/s)",
            )
    _COMPILED[key] = kernel
    return kernel


_COMPILED: dict[tuple[Any, ...], LawKernel] = {}
"""Kernels compiled from Python, by law class and numeric attributes (once per process)."""


def _attributes(law: Any) -> dict[str, Any]:
    """A law's instance attributes (``__dict__``, attrs fields or ``__slots__``)."""
    found: dict[str, Any] = dict(getattr(law, "__dict__", {}))
    if attrs.has(type(law)):
        found.update({f.name: getattr(law, f.name) for f in attrs.fields(type(law))})
    for slot in getattr(type(law), "__slots__", ()):
        if hasattr(law, slot):
            found[slot] = getattr(law, slot)
    return found
