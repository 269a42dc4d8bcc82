"""No output of a command destroys its inputs, its stores or its other outputs, and a
binary output replaces only a file of its own kind.

Each case once exited 0 having overwritten the file; every check now happens
before anything is computed (the computations here are stand-ins that record
whether they were reached).
"""

from __future__ import annotations

import os

import pytest

import tefcore.linear.stability
import tefcore.sweeps.evaluate
import tefcore.sweeps.maps
import tefcore.sweeps.sweep
import tefcore.timedomain.simulate
from tefcore.cli import main
from tefcore.config.io import load_config, save_config
from tefcore.safe_io import FileLock, check_outputs, same_file
from tests.sweeps.test_stability_map import Toy
from tests.sweeps.test_sweep import ToyPoint


class Started(Exception):
    """Raised by a stand-in: the computation would have started here."""


def one_error_line(capsys) -> str:
    err = capsys.readouterr().err
    assert err.startswith("tefcore: error: ") and err.count("\n") == 1, err
    return err


@pytest.fixture
def here(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.fixture
def toy(monkeypatch):
    point = ToyPoint()
    monkeypatch.setattr(tefcore.sweeps.sweep, "default_point", lambda: point)
    return point


@pytest.fixture
def toy_map(monkeypatch):
    point = Toy()
    for module in (tefcore.sweeps.sweep, tefcore.sweeps.maps, tefcore.sweeps.evaluate):
        monkeypatch.setattr(module, "default_point", lambda: point)
    return point


@pytest.fixture
def no_stability(monkeypatch):
    calls = []

    def stand_in(*a, **kw):
        calls.append(a)
        raise Started("stability")

    monkeypatch.setattr(tefcore.linear.stability, "stability", stand_in)
    return calls


@pytest.fixture
def no_simulate(monkeypatch):
    calls = []

    def stand_in(*a, **kw):
        calls.append(a)
        raise Started("simulate")

    monkeypatch.setattr(tefcore.timedomain.simulate, "simulate", stand_in)
    return calls


def _sweep_file(here, toy) -> bytes:
    """A finished sweep's file s.jsonl (its lock file beside it), as bytes."""
    assert main(["sweep", "flap.cg_offset", "--values", "0", "0.1", "--quiet", "--csv", "a.csv",
                 "--out", "s.jsonl"]) == 0
    assert (here / "s.jsonl.lock").exists()
    return (here / "s.jsonl").read_bytes()


# ------------------------------------------------------------------ outputs onto stores


def test_sweep_csv_onto_its_own_sweep_file(here, toy, capsys):
    # `sweep --out s.jsonl --csv s.jsonl` streamed the points, then wrote the CSV over them
    assert main(["sweep", "flap.cg_offset", "--values", "0", "0.1", "--quiet", "--out",
                 "s.jsonl", "--csv", "s.jsonl"]) == 2
    err = one_error_line(capsys)
    assert "--csv s.jsonl is the same file as --out s.jsonl" in err
    assert toy.calls == 0 and not (here / "s.jsonl").exists()


def test_sweep_csv_onto_its_own_sweep_file_through_another_spelling(here, toy, capsys):
    (here / "sub").mkdir()
    (here / "link").symlink_to(here / "sub")
    before = _sweep_file(here, toy)
    os.rename("s.jsonl", "sub/s.jsonl")
    assert main(["sweep", "flap.cg_offset", "--values", "0", "0.1", "--quiet", "--out",
                 "sub/s.jsonl", "--csv", "link/../sub/./s.jsonl"]) == 2
    assert "is the same file as --out sub/s.jsonl" in one_error_line(capsys)
    assert (here / "sub" / "s.jsonl").read_bytes() == before


def test_map_csv_onto_its_boundary_file(here, toy_map, capsys):
    # `map --out m --csv m/boundary.jsonl` replaced the boundary's store with the table
    argv = ["map", "flap.cg_offset", "0", "0.4", "3", "flap.overhang", "0", "0.2", "2",
            "--quiet", "--out", "m"]
    assert main([*argv, "--csv", "m/boundary.jsonl"]) == 2
    assert "--csv m/boundary.jsonl is the same file as --out m/boundary.jsonl" \
        in one_error_line(capsys)
    assert toy_map.calls == 0
    assert main(argv) == 0                                 # a map's files, then onto a row's
    before = (here / "m" / "row_1.jsonl").read_bytes()
    assert main([*argv, "--png", "m/row_1.jsonl"]) == 2
    assert "--png m/row_1.jsonl is the same file as --out m/row_1.jsonl" in one_error_line(capsys)
    assert (here / "m" / "row_1.jsonl").read_bytes() == before


def test_stability_csv_onto_a_sweep_file(here, toy, no_stability, capsys):
    # `stability --csv` onto another run's sweep file replaced its records
    before = _sweep_file(here, toy)
    assert main(["stability", "--csv", "s.jsonl"]) == 2
    err = one_error_line(capsys)
    assert "--csv s.jsonl is a file tefcore appends to and resumes" in err
    assert no_stability == [] and (here / "s.jsonl").read_bytes() == before


def test_stability_csv_onto_a_store_being_written(here, no_stability, capsys):
    (here / "s.jsonl").write_text('{"format": "tefcore.sweep"}\n')
    with FileLock(here / "s.jsonl", "sweep file"):           # another run writes it
        assert main(["stability", "--csv", "s.jsonl"]) == 2
    one_error_line(capsys)
    assert no_stability == [] and (here / "s.jsonl").read_text() == '{"format": "tefcore.sweep"}\n'


# ------------------------------------------------------------------ outputs onto inputs


def test_an_output_onto_the_configuration_file(here, no_stability, capsys):
    save_config(load_config("mdart"), here / "rotor.toml")
    before = (here / "rotor.toml").read_bytes()
    assert main(["stability", "--config", "rotor.toml", "--csv", "rotor.toml"]) == 2
    assert "--csv rotor.toml is the same file as --config rotor.toml, an input" \
        in one_error_line(capsys)
    os.link(here / "rotor.toml", here / "table.csv")       # the same file under another name
    assert main(["stability", "--config", "rotor.toml", "--csv", "table.csv"]) == 2
    assert "an input" in one_error_line(capsys)
    assert no_stability == [] and (here / "rotor.toml").read_bytes() == before


def test_an_output_onto_the_c81_deck_the_configuration_reads(here, no_stability, capsys):
    from tefcore.aero.c81 import example_deck_path

    deck = here / "deck.c81"
    deck.write_bytes(example_deck_path().read_bytes())
    assert main(["modes", "-s", "model.aero_model=c81", "-s", "model.c81_deck=deck.c81",
                 "--csv", "deck.c81"]) == 2
    assert "is the same file as model.c81_deck deck.c81, an input" in one_error_line(capsys)
    assert deck.read_bytes() == example_deck_path().read_bytes()


# ------------------------------------------------------------------ outputs onto outputs


def test_simulate_csv_and_json_onto_one_file(here, no_simulate, capsys):
    # `simulate --csv x --json x`: the JSON replaced the history, exit 0
    assert main(["simulate", "--csv", "x", "--json", "x"]) == 2
    assert "--json x and --csv x are the same file" in one_error_line(capsys)
    assert no_simulate == [] and not (here / "x").exists()


def test_map_outputs_onto_one_file(here, toy_map, capsys):
    assert main(["map", "flap.cg_offset", "0", "0.4", "3", "flap.overhang", "0", "0.2", "2",
                 "--quiet", "--csv", "m.out", "--png", "./m.out"]) == 2
    assert "are the same file" in one_error_line(capsys)
    assert toy_map.calls == 0


# ------------------------------------------------------------------ a file of another kind


def test_gif_does_not_replace_a_text_file(here, no_simulate, capsys):
    # `--gif notes.txt` overwrote the notes without asking
    (here / "notes.gif").write_text("my notes\n")
    assert main(["simulate", "--gif", "notes.gif"]) == 2
    assert "--gif notes.gif exists and is not a GIF file" in one_error_line(capsys)
    assert no_simulate == [] and (here / "notes.gif").read_text() == "my notes\n"
    # a previous animation (or an empty file) is replaced as before
    (here / "notes.gif").write_bytes(b"GIF89a" + bytes(20))
    (here / "empty.gif").write_bytes(b"")
    with pytest.raises(Started):
        main(["simulate", "--gif", "notes.gif", "--json", "empty.gif"])


@pytest.mark.parametrize("argv, name, kind", [
    (["fanplot", "--out", "plot.png"], "plot.png", "PNG"),
    (["fanplot", "--out", "plot.pdf"], "plot.pdf", "PDF"),
    (["map", "flap.cg_offset", "0", "0.4", "3", "flap.overhang", "0", "0.2", "2",
      "--png", "map.png"], "map.png", "PNG"),
    (["map", "flap.cg_offset", "0", "0.4", "3", "flap.overhang", "0", "0.2", "2",
      "--netcdf", "map.nc"], "map.nc", "netCDF"),
])
def test_an_image_or_dataset_does_not_replace_a_text_file(argv, name, kind, here, toy_map,
                                                          capsys):
    (here / name).write_text("not an image\n")
    assert main(argv) == 2
    assert f"{name} exists and is not a {kind} file" in one_error_line(capsys)
    assert (here / name).read_text() == "not an image\n" and toy_map.calls == 0


# ------------------------------------------------------------------ the helper


def test_check_outputs_compares_resolved_paths_and_inodes(tmp_path):
    a = tmp_path / "a.csv"
    a.write_text("x")
    os.link(a, tmp_path / "b.csv")
    assert same_file(a, tmp_path / "b.csv") and not same_file(a, tmp_path / "c.csv")
    assert same_file(tmp_path / "new.csv", tmp_path / "." / "new.csv")   # neither exists
    from tefcore.errors import OutputError

    with pytest.raises(OutputError, match="are the same file"):
        check_outputs([(a, "--csv"), (tmp_path / "b.csv", "--json")])
    with pytest.raises(OutputError, match="an input"):
        check_outputs([(tmp_path / "b.csv", "--csv")], inputs=[(a, "--config")])
    # the lock file of a store is the store's too
    with pytest.raises(OutputError, match="the lock file of --out"):
        check_outputs([(tmp_path / "s.jsonl.lock", "--csv")],
                      stores=[(tmp_path / "s.jsonl", "--out")])
    assert check_outputs([(None, "--csv"), (a, "--json")]) == [a]


def test_a_sweep_file_onto_the_configuration_file(here, toy, capsys):
    save_config(load_config("mdart"), here / "rotor.toml")
    before = (here / "rotor.toml").read_bytes()
    assert main(["sweep", "flap.cg_offset", "--values", "0", "--quiet", "--config", "rotor.toml",
                 "--out", "rotor.toml"]) == 2
    assert "--out rotor.toml is the same file as --config rotor.toml, an input" \
        in one_error_line(capsys)
    assert toy.calls == 0 and (here / "rotor.toml").read_bytes() == before
