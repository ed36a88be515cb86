"""The configuration, validated: :class:`Config` and its tables, and what they build.

A :class:`Config` (read from a file by :mod:`torsio.config.reading`) builds the structural
model (:meth:`Config.model`), its damping, the bit-rock law and the
:class:`~torsio.physics.system.System` of the analyzers (:meth:`Config.system`). The
objects of the model and the physics never read a configuration: this layer builds them.

Examples
--------
>>> from torsio.examples import builtin_config
>>> config = builtin_config()
>>> config.discretization.strategy, config.operation.rpm
('C', 100.0)
>>> system = config.system(strategy="A")
>>> system.model.dofs, round(system.omega, 4), system.wob
(1, 10.472, 100000.0)
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import attrs

from torsio.config.chain import ChainConfig
from torsio.config.tables import parse_rpm
from torsio.config.top_drive import TopDriveConfig
from torsio.errors import ConfigError
from torsio.model.drillstring import DrillString
from torsio.units import RPM_TO_RAD_S, to_si
from torsio.well.string_contacts import with_contacts
from torsio.well.wellbore import Wellbore

if TYPE_CHECKING:
    from torsio.config.axial import AxialConfig
    from torsio.physics.system import System

__all__ = [
    "BitRockConfig",
    "Config",
    "DampingConfig",
    "DiscretizationConfig",
    "OperationConfig",
    "SimulationConfig",
    "bit_radius",
]


@attrs.frozen
class BitRockConfig:
    """The ``[bit_rock]`` table: law name, bit radius [m] (None: bit od/2), parameters."""

    law: str = "tucker-wang"
    radius: float | None = None
    speed_unit: str = "rad/s"
    parameters: Mapping[str, float] = attrs.field(factory=dict)
    _built: list[Any] = attrs.field(factory=list, init=False, eq=False, repr=False)

    def build(self) -> Any:
        """The bit-rock law object (looked up among the registered laws), built once: the
        validation on reading the file builds it, every System of the table reuses it. A
        law that declares ``needs_axial`` (the RGD bit) is refused by key: the System is
        torsional only."""
        if not self._built:
            from torsio.plugins import build_bit_law

            self._built.append(build_bit_law(self.law, self.parameters, speed_unit=self.speed_unit))
        return self._built[0]


def bit_radius(bit_rock: BitRockConfig | None, string: Any) -> float:
    """R_bit [m]: ``[bit_rock] radius``, else half the outer diameter of the bit section of
    ``string`` (a ConfigError on ``bit_rock.radius`` with none: a ``[chain]``)."""
    if bit_rock is None or bit_rock.radius is None:
        if string is None:
            raise ConfigError(
                "bit_rock.radius", "required with [chain]: a chain has no bit section"
            )
        return float(string.bit.radius)
    return bit_rock.radius


@attrs.frozen
class DampingConfig:
    """The ``[damping]`` table: Rayleigh alpha [1/s] and beta [s], or modal damping ratios."""

    alpha: float | None = None
    beta: float | None = None
    ratios: tuple[float, float] | None = None
    modes: tuple[int, int] = (1, 2)


COUNTING_WAYS = (
    frozenset({"dp_elements", "bha_elements"}),
    frozenset({"section_elements"}),
    frozenset({"max_element_length"}),
)
"""The ways a discretizer's elements are counted; a file gives one of them."""


@attrs.frozen
class DiscretizationConfig:
    """The ``[discretization]`` table: strategy name and its element options."""

    strategy: str = "C"
    options: Mapping[str, Any] = attrs.field(factory=dict)

    def build(self) -> Any:
        """The discretizer object (looked up among the registered discretizers)."""
        from torsio.plugins import get_discretizer

        return get_discretizer(self.strategy)(**self.options)

    def of_axial_pipe(self) -> DiscretizationConfig:
        """These options as the distributed axial pipe (``strategy = "wave"`` with axial
        dynamics) takes them: its BHA rigid unless ``rigid_bha`` is given."""
        if self.strategy != "wave" or "rigid_bha" in self.options:
            return self
        return attrs.evolve(self, options={**self.options, "rigid_bha": True})

    def overridden(self, **overrides: Any) -> DiscretizationConfig:
        """These options with ``overrides`` (None: not given): ``strategy`` changes the
        strategy, and the table's options are kept only if it is unchanged; a count of
        elements given in one way (:data:`COUNTING_WAYS`) replaces those in the others.

        >>> given = DiscretizationConfig("B", {"dp_elements": 3})
        >>> given.overridden(bha_elements=2, strategy=None).options
        {'dp_elements': 3, 'bha_elements': 2}
        >>> given.overridden(strategy="A").options
        {}
        >>> DiscretizationConfig("C", {"max_element_length": 100.0}).overridden(dp_elements=5)
        DiscretizationConfig(strategy='C', options={'dp_elements': 5})
        """
        given = {k: v for k, v in overrides.items() if v is not None}
        strategy = given.pop("strategy", None) or self.strategy
        kept = dict(self.options) if strategy == self.strategy else {}
        for way in COUNTING_WAYS:
            if given.keys() & set().union(*(w for w in COUNTING_WAYS if w is not way)):
                kept = {k: v for k, v in kept.items() if k not in way}
        return DiscretizationConfig(strategy, {**kept, **given})


@attrs.frozen
class OperationConfig:
    """The ``[operation]`` table: weight on bit [N] and surface rotary speed [rpm]."""

    wob: float | None = None
    rpm: float | None = None

    @property
    def omega(self) -> float | None:
        """Surface rotary speed [rad/s]."""
        return None if self.rpm is None else self.rpm * RPM_TO_RAD_S


@attrs.frozen
class SimulationConfig:
    """The ``[simulation]`` table: options of :mod:`torsio.analysis.transient`."""

    options: Mapping[str, Any] = attrs.field(factory=dict)


@attrs.frozen
class Config:
    """A whole configuration file, validated.

    Exactly one of ``string`` (``[[section]]``) and ``chain`` (``[chain]``, a lumped
    model given directly) is set.
    """

    name: str
    string: DrillString | None
    bit_rock: BitRockConfig | None
    damping: DampingConfig
    discretization: DiscretizationConfig
    operation: OperationConfig
    simulation: SimulationConfig
    source: str = ""
    chain: ChainConfig | None = None
    top_drive: TopDriveConfig = attrs.field(factory=TopDriveConfig)
    well: Wellbore | None = None  # [well] (config/well.py); None: vertical, no contact
    axial: AxialConfig | None = None  # axial dynamics (config/axial.py); None: torsional only
    table: Mapping[str, Any] = attrs.field(factory=dict, eq=False, repr=False)
    """The file's tables as read (:func:`torsio.config.reading.rediscretized` reads them
    again)."""

    def model(self, **overrides: Any) -> Any:
        """Discretize the string: the configured strategy, with ``overrides`` of its options.

        ``strategy=...`` in ``overrides`` changes the strategy; options of the file
        are kept only if the strategy is unchanged.
        """
        if self.chain is not None:
            given = sorted(k for k, v in overrides.items() if v is not None)
            if given:
                raise ConfigError(
                    given[0], "the model is a [chain] given directly; it is not discretized"
                )
            return self.chain.model()
        assert self.string is not None
        return self.discretization.overridden(**overrides).build().discretize(self.string)

    @property
    def bit_radius(self) -> float:
        """R_bit [m]: ``bit_rock.radius``, else half the bit's outer diameter
        (:func:`bit_radius`)."""
        return bit_radius(self.bit_rock, self.string)

    def model_damping(self, model: Any) -> Any:
        """The damping of ``model``: the chain's own dampers, else ``[damping]`` (Rayleigh)."""
        from torsio.physics.damping import ModelDamping, RayleighDamping

        if self.chain is not None and self.chain.carries_damping:
            return ModelDamping()
        d = self.damping
        if d.ratios is not None:
            return RayleighDamping.from_modal_ratios(model, d.ratios, d.modes)
        return RayleighDamping(d.alpha or 0.0, d.beta or 0.0)

    def system(self, **discretization: Any) -> System:
        """The :class:`~torsio.physics.system.System` this configuration describes (the one
        way to build a System from a configuration).

        ``discretization`` overrides the ``[discretization]`` options; the operating
        point is ``[operation]`` (0 N and 60 rpm where absent; :meth:`System.at` sets
        another, :meth:`operating_point` reads a run's from arguments and the file); the
        top drive is ``[top_drive]`` (held at constant speed where absent).
        """
        from torsio.physics.system import System

        model = self.model(**discretization)
        op = self.operation
        wob = op.wob if op.wob is not None else 0.0
        if self.well is not None:  # the normal force at the file's weight on bit
            model = with_contacts(model, self.well, self.string, wob)
        damping = self.model_damping(model)
        return System(
            model=model,
            law=self.bit_law(),
            bit_radius=self.bit_radius,
            damping=damping,
            wob=wob,
            rpm=op.rpm if op.rpm is not None else 60.0,
            top=self.top_drive.build(),
            string=self.string,
        )

    def operating_point(self, wob: Any = None, rpm: Any = None) -> dict[str, float]:
        """The operating point of a dynamic run, as keywords of :meth:`System.at`.

        ``wob`` [N] and ``rpm`` may be numbers or strings with units (``"100 kN"``,
        ``"120 rpm"``) and override ``[operation]``; a clear error names the key where
        neither gives one. A top drive without a set speed (``torque``) takes no rpm.

        >>> from torsio.examples import builtin_config
        >>> builtin_config().operating_point(wob="175 kN")
        {'wob': 175000.0, 'rpm': 100.0}
        """
        if wob is None:
            wob = self.operation.wob
            if wob is None:
                raise ConfigError(
                    "operation.wob",
                    "no weight on bit: give one (e.g. --wob '100 kN') or set it in "
                    "the [operation] table",
                )
        else:
            text = wob
            wob = to_si(wob, "force", key="wob")
            if wob < 0:
                raise ConfigError("wob", f"expected a non-negative weight on bit, got {text!r}")
        if rpm is None and not self.top_drive.has_set_speed:  # e.g. a torque-driven top
            return {"wob": wob}
        if rpm is None:
            rpm = self.operation.rpm
            if rpm is None:
                raise ConfigError(
                    "operation.rpm",
                    "no rotary speed: give one (e.g. --rpm 120) or set it in the [operation] table",
                )
        else:
            rpm = parse_rpm(rpm, "rpm")
        return {"wob": wob, "rpm": rpm}

    def bit_law(self) -> Any:
        """The configured bit-rock law; a clear error if the file has no ``[bit_rock]`` table."""
        if self.bit_rock is None:
            raise ConfigError(
                "bit_rock",
                "the configuration has no [bit_rock] table; dynamic "
                "analyses need a bit-rock law (see `torsio laws`)",
            )
        return self.bit_rock.build()

    def off_bottom(self) -> Config:
        """This configuration, or for a file with axial dynamics its torsional model with the
        bit off bottom (:data:`OFF_BOTTOM`, no weight on bit; the same string, well and
        discretization: a distributed pipe's BHA rigid, as the axial pipe's).

        A start-up off bottom, as a fit's recordings are: the bit carries no torque whatever
        its law (the RGD bit's cutting and wear flats need weight on bit), and the string
        hangs still from the hook. With no axial sliding, each contact's Coulomb cone
        (:mod:`torsio.well.axial_contacts`) gives its whole capacity to the rotation, as a
        torsional contact does: on the file's discretization the torsional chain and its
        contacts are the axial chain's, so friction read on it (or on the continuum) is
        the friction of the axial model's well. (The axial engine itself does not run off
        bottom: its RGD bit needs a weight above the wear flats'.)

        Examples
        --------
        >>> from torsio.examples import rgd_deviated_well_config
        >>> config = rgd_deviated_well_config().off_bottom()
        >>> config.axial, config.bit_rock.law, config.model().dofs
        (None, 'constant', 24)
        """
        if self.axial is None:
            return self
        return attrs.evolve(
            self,
            axial=None,
            bit_rock=OFF_BOTTOM,
            operation=attrs.evolve(self.operation, wob=0.0),
            discretization=self.discretization.of_axial_pipe(),
        )


OFF_BOTTOM = BitRockConfig("constant", parameters={"torque_on_bit": 0.0})
"""The bit off bottom: no torque, whatever its law (:meth:`Config.off_bottom`)."""
