"""The distributed axial-torsional pipe from a configuration file (``[discretization]
strategy = "wave"`` with ``[bit_rock] law = "rgd"``): the built-in ``rgd_wave_pipe.toml``
through ``torsio.config.axial``, ``torsio report``, ``torsio simulate`` and ``torsio map``.

Independent references, each computed here from the file's numbers:

- the pipe sections and the BHA by hand: A = π (od² − id²)/4, J = π (od⁴ − id⁴)/32,
  m_b = Σ ρ A L and I_b = Σ ρ J L of the collars and the bit;
- the strategy-C chain of one section built from its E, G, ρ, A and J (``pipe_chain`` of
  tests/axial_files.py: :func:`torsio.model.axial_assembly.tube_section` above a rigid BHA);
- the natural frequencies of the stepped bar by its transfer matrix
  (U, N) → (U cos κL + N sin κL/(E A κ), −E A κ U sin κL + N cos κL), κ = ω/c, from the top
  (free: (1, 0); held: (0, 1)) to the BHA, whose balance N(L) = m_b ω² U(L) is solved by
  brentq (not the Wittrick-Williams count the report uses);
- the steady drilling state in closed form (RGD 2007, Teale 1965; torsio.axial.steady):
  d₀ = (W₀ − σ a l)/(ζ ε a), V₀ = Ω₀ d₀/2π, T₀ = ε a² d₀/2 + μ γ a² σ l/2,
  MSE = W₀/A_b + Ω₀ T₀/(A_b V₀), A_b = π a².
"""

from __future__ import annotations

import json
import math
import tomllib
from importlib import resources

import numpy as np
import pytest
import scipy.optimize
from axial_files import pipe_chain

from torsio.axial.wave_stability import distributed_stability
from torsio.cli import main
from torsio.config.axial import DEFAULT_ELEMENT_LENGTH
from torsio.config.reading import parse_config, parse_config_text
from torsio.errors import ConfigError
from torsio.examples import rgd_wave_pipe_config
from torsio.model.axial_assembly import lumped_twin, tube_section
from torsio.model.continuum import bar_frequencies
from torsio.model.discretize import StrategyC
from torsio.model.lumped import LumpedModel
from torsio.model.wave import WaveModel
from torsio.report.axial import axial_frequencies, axial_section, torsional_frequencies
from torsio.report.context import ReportContext
from torsio.solvers.axial_run_setup import RunOptions
from torsio.solvers.axial_wave_setup import wave_run_setup

TEXT = resources.files("torsio").joinpath("data/rgd_wave_pipe.toml").read_text(encoding="utf-8")
DATA = tomllib.loads(TEXT)
INCH = 0.0254
# the file's numbers: E, G [Pa], ρ [kg/m³]; (od, id, length) [m] of each section
E, G, RHO = 207e9, 79.3e9, 7850.0
PIPE = [(5 * INCH, 4.276 * INCH, 900.0), (5 * INCH, 3 * INCH, 100.0)]
BHA = [(6.75 * INCH, 2.8125 * INCH, 150.0), (8.5 * INCH, 0.0, 0.3)]
# the [bit_rock] table: a [m], ε, σ [Pa], ζ, l [m], μ, γ; the operating point W₀ [N]
RADIUS, EPSILON, SIGMA, ZETA, FLAT, MU, GAMMA = 0.108, 60e6, 60e6, 0.6, 0.011, 0.6, 1.0
WOB = 100e3


def _area(od: float, inner: float) -> float:
    return math.pi * (od**2 - inner**2) / 4


def _polar(od: float, inner: float) -> float:
    return math.pi * (od**4 - inner**4) / 32


BHA_MASS = sum(RHO * _area(od, i) * length for od, i, length in BHA)  # 22551.4 kg
BHA_INERTIA = sum(RHO * _polar(od, i) * length for od, i, length in BHA)  # 97.379 kg m²


def _text(old: str, new: str, text: str = TEXT) -> str:
    assert old in text, old
    return text.replace(old, new)


def _config(**replacements: str):
    text = TEXT
    for old, new in replacements.items():
        text = _text(old, new, text)
    return parse_config_text(text)


# --- the assembly -------------------------------------------------------------------------
def test_the_wave_pipe_is_the_files_sections():
    axial = rgd_wave_pipe_config().axial
    pipe = axial.assembly
    assert isinstance(pipe, WaveModel)
    assert pipe.lengths.tolist() == [900.0, 100.0]
    for section, (od, inner, _) in zip(pipe.sections, PIPE, strict=True):
        assert section.area == pytest.approx(_area(od, inner), rel=1e-14)
        assert section.polar_moment == pytest.approx(_polar(od, inner), rel=1e-14)
        material = section.material
        assert (material.youngs_modulus, material.shear_modulus, material.density) == (E, G, RHO)
    assert pipe.axial.bha_mass == pytest.approx(BHA_MASS, rel=1e-14)
    assert pipe.bit_inertia == pytest.approx(BHA_INERTIA, rel=1e-14)
    assert pipe.axial.hook == "weight" and pipe.travel_time_tolerance == 3e-4
    # the stability's lumped twin: the same sections in 100 m elements, no dampers
    twin = axial.lumped_twin
    assert isinstance(twin, LumpedModel) and twin.dofs == 10
    assert DEFAULT_ELEMENT_LENGTH == 100.0
    assert twin.axial.masses.sum() == pytest.approx(
        BHA_MASS + sum(RHO * _area(od, i) * length for od, i, length in PIPE), rel=1e-14
    )
    assert not twin.dampers.any() and not twin.axial.dampings.any()
    assert axial.stability_model == "lumped twin, 10 nodes (elements of at most 100 m)"
    # a section's own modulus and the travel-time tolerance are passed on
    own = _config(**{'bha = false': 'bha = false\nmaterial = { youngs_modulus = "200 GPa" }',
                     "travel_time_tolerance = 3e-4": "travel_time_tolerance = 1e-4"})  # fmt: skip
    assert [s.material.youngs_modulus for s in own.axial.assembly.sections] == [E, 200e9]
    assert own.axial.assembly.travel_time_tolerance == 1e-4


@pytest.mark.parametrize("hook", ["weight", "speed"])
def test_one_section_lumped_chain_is_the_pipe_chain(hook):
    # a one-section pipe + BHA through the file (no [discretization]: the lumped chain,
    # 1000 m in 250 m elements) against pipe_chain(4, ...) of the same data (the pipe given
    # by its E, G, ρ, A and J, the BHA by its mass and inertia) and against
    # the lumped-mass rule written out (each element's ρAΔ and ρJΔ halved onto its end
    # nodes, the BHA on the last): under the weight hook the free top's half element rides
    # on node 0; torsionally (and axially under the speed hook) that half is at the top
    data = tomllib.loads(TEXT)
    del data["discretization"]
    data["section"] = [data["section"][0], *data["section"][2:]]
    data["section"][0]["length"] = "1000 m"
    data["axial"] = {"hook": hook, "element_length": "250 m"}
    chain = parse_config(data).axial.assembly
    od, inner, _ = PIPE[0]
    area, polar = _area(od, inner), _polar(od, inner)
    section = tube_section(1000.0, E, G, RHO, area, polar)
    expected = pipe_chain(4, section, BHA_MASS, BHA_INERTIA, hook=hook)
    spacing, bottom = 250.0, np.array([0.0, 0.0, 0.0, 1.0])
    halves = np.array([2.0, 2.0, 2.0, 1.0]) + (hook == "weight") * np.array([1.0, 0, 0, 0])
    by_hand = {
        lambda a: a.axial.masses: halves / 2 * RHO * area * spacing + bottom * BHA_MASS,
        lambda a: a.node_inertias: np.array([1.0, 1.0, 1.0, 0.5]) * RHO * polar * spacing
        + bottom * BHA_INERTIA,
        lambda a: a.springs: np.full(4, G * polar / spacing),
        lambda a: a.axial.stiffnesses: np.full(4, E * area / spacing),
    }
    for rows, values in by_hand.items():
        np.testing.assert_allclose(rows(chain), values, rtol=1e-14)
        np.testing.assert_allclose(rows(expected), values, rtol=1e-14)
    assert chain.axial.hook == hook and not chain.dampers.any()


@pytest.mark.parametrize("element_length", [100.0, 70.0, 333.0])
def test_the_pipes_lumped_twin_is_the_files_strategy_c_chain(element_length):
    # two routes to the lumped-mass chain of the file's stepped string (900 m of drill pipe
    # and 100 m of HWDP in the pipe, the collars and the bit rigid): the file without
    # strategy = "wave" (the paper's strategy C, Eqs. 6-7, with axial rows) and the
    # distributed pipe's lumped twin (torsio.model.axial_assembly.lumped_twin, built from the
    # wave model); the same element counts, node depths, springs and inertias to
    # round-off, the same masses and axial springs
    data = tomllib.loads(TEXT)
    del data["discretization"]
    data["axial"] = {"element_length": element_length}
    axial = parse_config(data).axial
    chain = axial.assembly
    model = StrategyC(max_element_length=element_length).discretize(axial.string)
    np.testing.assert_array_equal(chain.stiffness, model.stiffness)
    twin = lumped_twin(rgd_wave_pipe_config().axial.assembly, element_length)
    assert twin.dofs == chain.dofs
    for rows in ("inertia", "stiffness", "node_depths"):
        np.testing.assert_allclose(getattr(twin, rows), getattr(chain, rows), rtol=1e-14)
    for rows in ("masses", "stiffnesses"):
        np.testing.assert_allclose(
            getattr(twin.axial, rows), getattr(chain.axial, rows), rtol=1e-14
        )


# --- the report's frequencies -------------------------------------------------------------
def _transfer_roots(rigidities, lengths, speeds, tip, count, free_top):
    """The first ``count`` nonzero ω [rad/s] of the stepped bar (transfer matrix, brentq)."""

    def balance(omega: float) -> float:
        u, n = (1.0, 0.0) if free_top else (0.0, 1.0)
        for rigidity, length, c in zip(rigidities, lengths, speeds, strict=True):
            k, x = rigidity * omega / c, omega * length / c
            u, n = u * math.cos(x) + n * math.sin(x) / k, -k * u * math.sin(x) + n * math.cos(x)
        return n - tip * omega**2 * u

    grid = np.linspace(1e-3, 200.0, 40001)  # 5 mrad/s apart: far below the roots' spacing
    values = [balance(w) for w in grid]
    roots = [
        scipy.optimize.brentq(balance, a, b, xtol=1e-13, rtol=1e-15)
        for a, b, fa, fb in zip(grid, grid[1:], values, values[1:], strict=False)
        if fa * fb < 0
    ]
    return np.array(roots[:count])


def _lines(pipe):
    rows, sections = pipe.axial, pipe.sections
    axial = [s.material.youngs_modulus * s.area for s in sections]
    torsional = [s.material.shear_modulus * s.polar_moment for s in sections]
    return {
        "axial": (axial, rows.wave_speeds, rows.bha_mass),
        "torsional": (torsional, pipe.wave_speeds, pipe.bit_inertia),
    }


def test_the_reports_frequencies_are_the_stepped_bars_continuum():
    config = rgd_wave_pipe_config()
    pipe = config.axial.assembly
    data = axial_section(ReportContext(config)).data
    lines = _lines(pipe)
    # torsional: the top drive held, the bit free; axial under the weight hook: top free
    # (the rigid-body zero left out); both in Hz. Measured: within 2.6e-15 (torsional),
    # 2.4e-15 (axial, top free) and 4.1e-15 (axial, top held) of the transfer-matrix roots
    torsional = 2 * math.pi * np.array(data["torsional_frequencies_hz"])
    rigidity, speeds, tip = lines["torsional"]
    reference = _transfer_roots(rigidity, pipe.lengths, speeds, tip, 5, free_top=False)
    np.testing.assert_allclose(torsional, reference, rtol=1e-13)
    axial = 2 * math.pi * np.array(data["axial_frequencies_hz"])
    rigidity, speeds, tip = lines["axial"]
    reference = _transfer_roots(rigidity, pipe.lengths, speeds, tip, 5, free_top=True)
    np.testing.assert_allclose(axial, reference, rtol=1e-13)
    # measured: 0.4224 ... 6.564 Hz torsionally, 1.741 ... 11.98 Hz axially (0.7211 ...
    # 10.78 Hz with the top held)
    assert data["torsional_frequencies_hz"][0] == pytest.approx(0.4224, abs=5e-5)
    assert data["axial_frequencies_hz"][0] == pytest.approx(1.741, abs=5e-4)
    assert data["stability"]["stability_model"].startswith("lumped twin, 10 nodes")
    # under the speed hook the top is held: the Wittrick-Williams bar_frequencies
    held = _config(**{'hook = "weight"': 'hook = "speed"'}).axial.assembly
    np.testing.assert_allclose(
        2 * math.pi * np.array(axial_frequencies(held, 5)),
        _transfer_roots(rigidity, pipe.lengths, speeds, tip, 5, free_top=False),
        rtol=1e-13,
    )
    np.testing.assert_allclose(
        2 * math.pi * np.array(axial_frequencies(held, 5)),
        bar_frequencies(rigidity, pipe.lengths, speeds, tip, 5),
        rtol=1e-13,
    )


@pytest.mark.parametrize("line", ["axial", "torsional"])
def test_the_runs_grid_is_within_the_travel_time_rounding_of_the_report(line):
    # the run steps the pipe of lengths n h c (travel times rounded to whole steps); its
    # exact frequencies differ from the report's by at most the largest relative rounding
    # (Rayleigh's quotient, docs/axial.md "What the rounding costs"). Measured at 60 rpm:
    # h = 1.498 ms, axial cells (117, 13) with travel times rounded by 1.67e-4, torsional
    # cells (189, 21) exact
    config = rgd_wave_pipe_config()
    pipe, bit = config.axial.assembly, config.axial.bit
    grid = wave_run_setup(pipe, bit, WOB, 60.0, RunOptions(1.0, 0.5)).grid
    rigidity, speeds, tip = _lines(pipe)[line]
    cells = np.array(getattr(grid, f"{line}_cells"))
    free_top = line == "axial"
    rounded = bar_frequencies(rigidity, cells * grid.step * speeds, speeds, tip, 5,
                              free_top=free_top)  # fmt: skip
    report = {"axial": axial_frequencies, "torsional": torsional_frequencies}[line](pipe, 5)
    rounding = grid.travel_time_errors[0 if free_top else 1].max()
    assert rounding <= 3e-4
    assert np.all(np.abs(rounded / (2 * math.pi * np.array(report)) - 1) <= rounding)


# --- the commands -------------------------------------------------------------------------
def _run_json(capsys, *args):
    status = main([*args, "--json"])
    captured = capsys.readouterr()
    assert status == 0, captured.err
    return json.loads(captured.out)


def _steady_file(tmp_path, text: str, name: str) -> str:
    path = tmp_path / name
    path.write_text(
        _text('start = "rest"                 # rest | steady',
              'start = "steady"\nperturbation = 0.0', text),
        encoding="utf-8",
    )  # fmt: skip
    return str(path)


def _closed_form(rpm: float) -> tuple[float, float]:
    omega = rpm * math.pi / 30
    depth = (WOB - SIGMA * RADIUS * FLAT) / (ZETA * EPSILON * RADIUS)  # 7.3868 mm/rev
    rop = omega * depth / (2 * math.pi)
    torque = EPSILON * RADIUS**2 * depth / 2 + MU * GAMMA * RADIUS**2 * SIGMA * FLAT / 2
    area = math.pi * RADIUS**2
    return rop, WOB / area + omega * torque / (area * rop)


RUN = ["--rpm", "180", "--duration", "4", "--window", "2"]


def test_simulate_json_of_a_steady_start_stays_at_the_steady_state(capsys, tmp_path):
    # started on the steady state with no perturbation, the distributed pipe stays there.
    # Measured at 180 rpm over 4 s (h = 1.498 ms, about 2700 steps): rop_mean/V0 - 1 =
    # -7.6e-14, mse_mean/MSE0 - 1 = 6.8e-14, S_SS 9.8e-15, axial severity 2.7e-13. The
    # bound 2e-12: the round-off of N = 2700 steps, N x 1.1e-16 = 3e-13, grown at most by
    # e^(0.45 x 4) = 6 (0.45 1/s: the lumped twin's growth rate there; the steady state is
    # unstable, so round-off is not damped)
    data = _run_json(capsys, "simulate", _steady_file(tmp_path, TEXT, "wave.toml"), *RUN)
    rop, mse = _closed_form(180.0)
    assert data["steady_state"]["rop"] == pytest.approx(rop, rel=1e-14)
    assert data["steady_state"]["mse"] == pytest.approx(mse, rel=1e-14)
    assert data["rop_mean"] == pytest.approx(rop, rel=2e-12)
    assert data["mse_mean"] == pytest.approx(mse, rel=2e-12)
    assert data["severity"] < 2e-12 and data["axial_severity"] < 2e-12
    assert data["stick_fraction"] == 0.0 and data["off_bottom_fraction"] == 0.0
    # the growth rate of the pipe's own characteristic equation (test_axial_wave_stability)
    axial = rgd_wave_pipe_config().axial
    exact = distributed_stability(axial.assembly, axial.bit, data["wob"], 180.0,
                                  twin=axial.stability_assembly)  # fmt: skip
    assert data["growth_rate"] == exact.growth_rate
    assert data["model"]["kind"] == "distributed" and len(data["model"]["sections"]) == 2


def test_the_wave_and_the_lumped_file_agree_on_steady_rop_and_mse(capsys, tmp_path):
    wave = _run_json(capsys, "simulate", _steady_file(tmp_path, TEXT, "wave.toml"), *RUN)
    lumped_text = _text('strategy = "wave"', 'strategy = "C"')
    lumped_text = _text("travel_time_tolerance = 3e-4", "", lumped_text)
    lumped = _run_json(capsys, "simulate", _steady_file(tmp_path, lumped_text, "chain.toml"), *RUN)
    assert lumped["model"]["kind"] == "lumped" and lumped["model"]["nodes"] == 10
    # both at the closed form to round-off (measured: wave -7.6e-14 and 6.8e-14, lumped
    # -1.5e-14 and -4.7e-14 relative; the bound as in the test above)
    for key in ("rop_mean", "mse_mean"):
        assert wave[key] == pytest.approx(lumped[key], rel=4e-12), key
    assert wave["steady_state"] == lumped["steady_state"]
    # the lumped run has its own growth rate: the rightmost root of the 10-node chain
    # (measured 0.44600 1/s, undamped: the twin of the distributed pipe, whose own is 0.4644)
    assert lumped["growth_rate"] == pytest.approx(0.446, abs=1e-3)


def test_map_and_report_run_the_wave_file(capsys):
    path = str(resources.files("torsio").joinpath("data/rgd_wave_pipe.toml"))
    grid = _run_json(capsys, "map", path, "--wob", "90kN:110kN:2", "--rpm", "60:180:2",
                     "--duration", "2", "--window", "1", "--threads", "1")  # fmt: skip
    assert np.array(grid["rop"]).shape == (2, 2)
    assert np.all(np.isfinite(np.array(grid["growth_rate"], dtype=float)))
    assert grid["info"]["model"]["kind"] == "distributed"
    report = _run_json(capsys, "report", path)
    assert report["axial"]["stability"]["stability_model"].startswith("lumped twin")
    assert main(["report", path]) == 0
    text = " ".join(capsys.readouterr().out.split())  # the table's wrapping aside
    assert "distributed pipe, 2 section(s), 1000 m" in text
    assert "crossings computed on lumped twin, 10 nodes" in text
    assert "(bit free, top free)" in text


# --- refusals -----------------------------------------------------------------------------
REFUSALS = [
    ({"[axial]\nhook": '[axial]\nelement_length = "50 m"\nhook'}, "axial.element_length",
     "no elements"),
    ({"[operation]": "[damping]\nbeta = 0.06\n[operation]"}, "damping.beta",
     "the distributed axial pipe has no damping yet"),
    ({"[operation]": "[damping]\nalpha = 0.35\n[operation]"}, "damping.alpha",
     "the distributed axial pipe has no damping yet"),
    ({'youngs_modulus = "207 GPa"': ""}, "material.youngs_modulus", "missing"),
    ({"travel_time_tolerance = 3e-4": "time_step = 1e-3"}, "discretization.time_step",
     "simulation.step"),
    ({"travel_time_tolerance = 3e-4": "drag_spacing = 2"}, "discretization.drag_spacing",
     "no distributed drag"),
    ({"travel_time_tolerance = 3e-4": "rigid_bha = false"}, "discretization.rigid_bha",
     "one rigid body"),
    ({"travel_time_tolerance = 3e-4": "travel_time_tolerance = 0.7"},
     "discretization.travel_time_tolerance", "(0, 0.5)"),
    ({"travel_time_tolerance = 3e-4": "dp_elements = 5"}, "discretization.dp_elements",
     "wave strategy takes no option"),
]  # fmt: skip


@pytest.mark.parametrize(("replacements", "key", "message"), REFUSALS)
def test_what_the_wave_pipe_does_not_take_is_refused_by_key(replacements, key, message):
    with pytest.raises(ConfigError) as info:
        _config(**replacements)
    assert info.value.key == key
    assert message in info.value.message
    # the zero damping of a [damping] table is no damping: accepted
    assert _config(**{"[operation]": "[damping]\nbeta = 0.0\n[operation]"}).axial is not None


def test_beta_stays_with_the_lumped_chain():
    text = _text('strategy = "wave"', 'strategy = "C"')
    text = _text("travel_time_tolerance = 3e-4", "", text)
    chain = parse_config_text(_text("[operation]", "[damping]\nbeta = 0.06\n[operation]", text))
    assembly = chain.axial.assembly
    np.testing.assert_allclose(assembly.dampers, 0.06 * assembly.springs, rtol=1e-15)
    assert chain.axial.lumped_twin is None and chain.axial.stability_model == "the assembly"
