"""mjarm.replay_html: a recording's replay page from Python, the same file and report as
`mjarm replay-html --json` (docs/python.md, docs/replay.md); bad input raises mjarm.Error."""
import json
import os
import subprocess

import pytest

import mjarm
from mjarm.__main__ import cli_path


@pytest.fixture(scope="module")
def recording(tmp_path_factory):
    """A short shelf pick of the planar arm, recorded (its model.mjb kept beside the CSVs)."""
    folder = tmp_path_factory.mktemp("replay") / "pick"
    options = mjarm.ShelfPickOptions()
    options.request.robot = "planar2"
    options.request.controller = "osc"
    options.settle_time = 0.3
    options.record = str(folder)
    assert mjarm.run_shelf_pick(options).ok()
    return folder


def test_the_page_and_report_are_the_clis(recording, tmp_path):
    page = tmp_path / "page.html"
    if not mjarm.replay_html_available():  # a build without node and npm: said, nothing written
        with pytest.raises(mjarm.Error, match="built without the replay page"):
            mjarm.replay_html(recording, page)
        assert not page.exists()
        return
    report = mjarm.replay_html(recording, page, rate=30.0, title="a pick")
    assert isinstance(report, dict)
    assert report["path"] == str(page) and report["recording"] == str(recording)
    assert report["bytes"] == os.path.getsize(page) > 0
    assert abs(report["rate"] - 30.0) < 3.0 and report["frames"] > 1
    assert report["drawn_geoms"] > 0 and report["bodies"] > 1
    html = page.read_text()
    assert html.startswith("<!doctype html>") and "<title>a pick" in html

    cli_page = tmp_path / "cli.html"
    # the CLI itself (python -m mjarm forwards to it: test_tasks_render_cli.py)
    out = subprocess.run([cli_path(), "replay-html", str(recording), "-o",
                          str(cli_page), "--rate", "30", "--title", "a pick", "--json"],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    cli = json.loads(out.stdout)
    assert list(cli) == list(report)  # the same keys, in the same order
    assert {**cli, "path": None} == {**report, "path": None}
    assert cli_page.read_bytes() == page.read_bytes()


def test_another_model_may_be_named(recording, tmp_path):
    if not mjarm.replay_html_available():
        return
    planar2 = mjarm.Robot.load("planar2")
    report = mjarm.replay_html(recording, tmp_path / "named.html", model=planar2)
    assert report["bytes"] == os.path.getsize(tmp_path / "named.html")


def test_bad_input_raises_and_writes_nothing(recording, tmp_path):
    page = tmp_path / "bad.html"
    with pytest.raises(mjarm.Error, match="no_such_recording"):
        mjarm.replay_html(tmp_path / "no_such_recording", page)
    if mjarm.replay_html_available():
        with pytest.raises(mjarm.Error, match="does not match the recording"):
            mjarm.replay_html(recording, page, model=mjarm.Robot.load("arm6"))
        with pytest.raises(mjarm.Error, match="rate"):
            mjarm.replay_html(recording, page, rate=0.0)
        with pytest.raises(mjarm.Error, match="no_folder"):
            mjarm.replay_html(recording, tmp_path / "no_folder" / "x.html")
    assert not page.exists()
