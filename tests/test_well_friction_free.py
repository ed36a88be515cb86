"""Wells without friction along the string run on every engine, as without contacts, and say so.

Issue 36, case 1: a vertical ``[well]``, friction factors 0, or mud as dense as the steel
(buoyed weight 0, so no normal force off bottom) carry no friction at any contact; the
lumped engines crashed (``KeyError: 'friction_work'``) and the wave model and ``torsio map``
refused with a ``discretization.drag_spacing`` error. Expected: the run of the same string
without ``[well]`` (no contact force: identical equations), and a warning.
"""

from __future__ import annotations

import json
import re
from importlib import resources

import numpy as np
import pytest

from torsio.cli import main
from torsio.config.reading import load_config
from torsio.model.contacts import StringContacts, carried_contacts

WARNING = "no contact along the string carries friction"


def _deviated() -> str:
    return resources.files("torsio").joinpath("data/deviated_well.toml").read_text("utf-8")


def _variant(name: str) -> str:
    text = _deviated()
    if name == "vertical":
        return re.sub(r"inclination = \[[^\]]*\]", "inclination = [" + ", ".join(["0.0"] * 8) + "]",
                      text)  # fmt: skip
    if name == "mu0":
        return re.sub(r"friction_(static|dynamic) = [0-9.]+", r"friction_\1 = 0.0", text)
    assert name == "steel_mud"  # the steel's density (7850 kg/m^3, [material])
    return text.replace("mud_density = 1200.0", "mud_density = 7850.0")


def _without_well(text: str) -> str:
    head, _, rest = text.partition("[well]")
    return head + "[bit_rock]" + rest.partition("[bit_rock]")[2]


def _simulate(capsys, path, *extra: str) -> dict:
    argv = ["simulate", str(path), "--wob", "0", "--rpm", "60", "--duration", "3", "--json"]
    assert main([*argv, *extra]) == 0
    captured = capsys.readouterr()
    return {"data": json.loads(captured.out), "err": captured.err}


@pytest.mark.parametrize("name", ["vertical", "mu0", "steel_mud"])
@pytest.mark.parametrize("engine", [("--strategy", "C"), ()], ids=["lumped", "wave"])
def test_runs_as_without_contacts_and_says_so(capsys, tmp_path, name, engine):
    path, bare = tmp_path / "well.toml", tmp_path / "bare.toml"
    path.write_text(_variant(name), "utf-8")
    bare.write_text(_without_well(_variant(name)), "utf-8")
    run = _simulate(capsys, path, *engine)
    reference = _simulate(capsys, bare, *engine)["data"]
    assert any(WARNING in text for text in run["data"]["warnings"])
    assert WARNING in run["err"]
    assert not any(WARNING in text for text in reference["warnings"])
    # no contact force: the equations of the string without [well], so the same numbers
    for key in ("severity", "stick_fraction", "mean_bit_speed"):
        if key in reference:
            assert run["data"][key] == pytest.approx(reference[key], rel=1e-12, abs=1e-12)


def test_map_runs_and_says_so(capsys, tmp_path):
    path = tmp_path / "well.toml"
    path.write_text(_variant("vertical"), "utf-8")
    argv = ["map", str(path), "--strategy", "C", "--dp-elements", "4", "--bha-elements", "1",
            "--wob", "50kN:100kN:2", "--rpm", "60:100:2", "--duration", "5", "--json"]  # fmt: skip
    assert main(argv) == 0
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    assert any(WARNING in text for text in data["warnings"])
    assert np.isfinite(np.asarray(data["severity"], dtype=float)).all()


def test_contacts_without_friction_leave_the_engines():
    # zero capacities everywhere: no contact (StringContacts.count counts C_s > 0)
    none = StringContacts(static=np.zeros(4), dynamic=np.zeros(4))
    assert carried_contacts(none)[0] is None and WARNING in carried_contacts(none)[1]
    some = StringContacts(static=np.array([0.0, 1.0]), dynamic=np.array([0.0, 1.0]))
    assert carried_contacts(some) == (some, None)


def test_wave_grid_of_a_vertical_well_has_zero_capacities(tmp_path):
    # a vertical hole: no inclination, no curvature, so N = 0 (Johancsik et al. 1984)
    path = tmp_path / "well.toml"
    path.write_text(_variant("vertical"), "utf-8")
    contacts = load_config(path).system().model.contacts
    assert contacts.static_total == 0.0 and contacts.dynamic_total == 0.0
