"""Mission <-> scene identity: the shipped folders fit their own scene and no other (30 combinations)."""

from __future__ import annotations

from pathlib import Path

import pytest

from sgplan.cli import main
from sgplan.errors import SceneMismatchError
from sgplan.mission import read_ap_desc
from sgplan.mission.identity import check_folder_scene, ensure_folder_fits_scene, scene_graph_hash
from sgplan.scene.demo import demo_building

SCENES = ("Allensville", "Benevolence", "Collierville")


def test_graph_hash_is_stable_and_sees_a_renamed_room() -> None:
    building = demo_building()
    before = scene_graph_hash(building)
    assert before == scene_graph_hash(demo_building())
    building.room(uuid=4).name = "bathroom"
    assert scene_graph_hash(building) != before


def test_folder_without_any_record_cannot_be_checked(tmp_path: Path) -> None:
    fit = check_folder_scene(tmp_path, {}, demo_building())
    assert fit.fits and fit.source == "nothing" and "could not be checked" in fit.notes[0]


@pytest.mark.gibson
def test_shipped_folders_fit_only_their_own_scene(gibson_root: Path) -> None:
    from sgplan.formats import load_scene

    buildings = {name: load_scene(gibson_root / name) for name in SCENES}
    refused = 0
    for origin in SCENES:
        for number in range(1, 6):
            folder = gibson_root / origin / "missions" / str(number)
            props = read_ap_desc(folder / "ap_desc.yaml")
            assert ensure_folder_fits_scene(folder, props, buildings[origin]).fits
            for other in SCENES:
                if other == origin:
                    continue
                with pytest.raises(SceneMismatchError, match=f"does not fit scene '{other}'"):
                    ensure_folder_fits_scene(folder, props, buildings[other])
                refused += 1
                forced = ensure_folder_fits_scene(folder, props, buildings[other], force=True)
                assert "planning anyway (--force)" in forced.notes[-1]
    assert refused == 30


@pytest.mark.gibson
def test_plan_refuses_a_shipped_folder_on_another_scene(
    gibson_root: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    folder = gibson_root / "Allensville" / "missions" / "4"
    assert (
        main(["plan", "--scene", "Collierville", "--data", str(gibson_root), "--mission-dir", str(folder)])
        == 2
    )
    err = capsys.readouterr().err
    assert "room_10 was a dining room on floor 0, but in 'Collierville' it is a corridor on floor 1" in err
