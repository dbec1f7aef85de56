"""The semantic map scorer: matches, and the reason given for each false and missed object."""
import importlib.util
import pathlib

_SPEC = importlib.util.spec_from_file_location(
    "score_semantic", pathlib.Path(__file__).with_name("score_semantic.py"))
score_semantic = importlib.util.module_from_spec(_SPEC)
_SPEC.loader.exec_module(score_semantic)

WORLD = score_semantic.world_objects([
    {"class": "chair", "x": 0.0, "y": 0.0, "width": 0.5, "depth": 0.5},
    {"class": "table", "x": 3.0, "y": 0.0, "width": 1.4, "depth": 0.7},
    {"class": "bed", "x": 6.0, "y": 0.0, "width": 1.0, "depth": 2.0},
    {"class": "stool", "x": 10.0, "y": 0.0, "radius": 0.2},
])


def mapped(name: str, x: float, y: float, observations: int) -> dict:
    return {"class": name, "center": [x, y], "observations": observations}


def test_every_false_and_missed_object_gets_its_reason() -> None:
    result = score_semantic.score([
        mapped("chair", 0.2, 0.1, 3),    # the chair again, seen in fewer frames
        mapped("chair", 0.1, 0.0, 10),   # the chair
        mapped("table", 3.6, 0.0, 8),    # the table, 0.6 m off
        mapped("sofa", 6.05, 0.0, 8),    # the bed, misnamed
        mapped("computer", 20.0, 20.0, 5),
    ], WORLD, max_distance=0.3, near=1.0)
    assert result["matched"] == 1
    assert result["precision"] == 0.2
    assert result["recall"] == 0.25
    assert abs(result["mean_centre_error_m"] - 0.1) < 1e-12
    why = {(o["class"], round(o["center"][0], 2)): o["why"] for o in result["unmatched_map_objects"]}
    assert why == {("chair", 0.2): "mapped twice", ("table", 3.6): "offset",
                   ("sofa", 6.05): "wrong class", ("computer", 20.0): "nothing near"}
    missed = {o["class"]: o["why"] for o in result["missed_world_objects"]}
    assert missed == {"table": "offset", "bed": "wrong class", "stool": "not mapped"}
    assert result["false_why"] == {"mapped twice": 1, "offset": 1, "wrong class": 1,
                                   "nothing near": 1}


def test_two_entries_off_one_object_are_one_offset_and_one_twice() -> None:
    # A bed split in two halves, each 0.5 m from its centre: neither matches, the one seen in
    # more frames claims it.
    result = score_semantic.score([mapped("bed", 5.5, 0.0, 20), mapped("bed", 6.5, 0.0, 30)],
                                  WORLD, max_distance=0.3, near=1.0)
    why = {o["center"][0]: o["why"] for o in result["unmatched_map_objects"]}
    assert why == {6.5: "offset", 5.5: "mapped twice"}


def test_the_best_seen_object_takes_the_match() -> None:
    result = score_semantic.score([mapped("stool", 10.25, 0.0, 2), mapped("stool", 10.1, 0.0, 9)],
                                  WORLD, max_distance=0.3, near=1.0)
    assert abs(result["mean_centre_error_m"] - 0.1) < 1e-12
    assert [o["why"] for o in result["unmatched_map_objects"]] == ["mapped twice"]


def test_a_file_it_cannot_read_is_one_line_and_exit_2(tmp_path: pathlib.Path) -> None:
    import subprocess
    import sys

    world = tmp_path / "world.yaml"
    world.write_text("objects:\n  - {class: chair, x: 0, y: 0, width: 0.5, depth: 0.5}\n")
    bad = tmp_path / "semantic.json"
    bad.write_text('{"objects": [{"class": "chair"}]}')
    good = tmp_path / "good.json"
    good.write_text('{"objects": [{"class": "chair", "center": [0.1, 0.0]}]}')
    script = pathlib.Path(__file__).with_name("score_semantic.py")
    for args, named in (([bad, world], bad), ([tmp_path / "none.json", world], "none.json"),
                        ([good, tmp_path / "none.yaml"], "none.yaml")):
        run = subprocess.run([sys.executable, str(script), *map(str, args)], capture_output=True,
                             text=True)
        assert run.returncode == 2
        assert run.stdout == "" and len(run.stderr.splitlines()) == 1
        assert str(named) in run.stderr
    ok = subprocess.run([sys.executable, str(script), str(good), str(world)], capture_output=True)
    assert ok.returncode == 0
