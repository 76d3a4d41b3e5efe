"""The on-disk scene cache: a warm load gives the same building and grid without reading the scene again;
any change of an input file (or a broken entry) rebuilds; it can be turned off; unsafe folders are unused."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from sgplan.formats import load_scene
from sgplan.scene import authors, cache, grid
from tests.scene.synthetic import SyntheticScene, assert_same_building, synthetic_scene


@pytest.fixture
def cache_folder(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    folder = tmp_path / "cache"
    monkeypatch.setenv(cache.DIR_ENV, str(folder))
    monkeypatch.delenv(cache.OFF_ENV, raising=False)
    return folder


@pytest.fixture
def loads(monkeypatch: pytest.MonkeyPatch) -> list[Path]:
    """Every real (uncached) load of an authors' scene, recorded."""
    calls: list[Path] = []
    real = authors.load_authors_scene_with_inputs

    def counting(path: str | Path) -> tuple:
        calls.append(Path(path))
        return real(path)

    monkeypatch.setattr(authors, "load_authors_scene_with_inputs", counting)
    return calls


@pytest.fixture
def grid_builds() -> list[float]:
    """The radii of every real grid build through :func:`_grid`."""
    return []


def _grid(building: object, radius: float, builds: list[float]) -> grid.OccupancyGrid:
    def counting(b: object, r: float) -> grid.OccupancyGrid:
        builds.append(r)
        return grid.build_occupancy_grid(b, r)  # type: ignore[arg-type]

    return cache.occupancy_grid_cached(building, radius, counting)  # type: ignore[arg-type]


def test_warm_load_is_the_same_building_without_reading_the_scene(
    tmp_path: Path, cache_folder: Path, loads: list[Path]
) -> None:
    folder = synthetic_scene().write(tmp_path / "tiny")
    cold = load_scene(folder)
    warm = load_scene(folder)
    assert len(loads) == 1 and warm is not cold
    assert_same_building(cold, warm)
    assert warm.source == folder and warm.initial_cells == cold.initial_cells
    assert len(list(cache_folder.glob(f"building-*{cache.SUFFIX}"))) == 1


def _rename(scene: SyntheticScene) -> None:
    scene.document["name"] = "Tinier"


def _wall(scene: SyntheticScene) -> None:
    scene.cat_maps[1][0, 8] = -3


def _radius(scene: SyntheticScene) -> None:
    scene.radius_config = "ROBOT_RADIUS=0.05\n"


@pytest.mark.parametrize("change", [_rename, _wall, _radius], ids=["yaml", "map", "radius-file"])
def test_any_changed_input_rebuilds(tmp_path: Path, cache_folder: Path, loads: list[Path], change) -> None:
    scene = synthetic_scene()
    folder = scene.write(tmp_path / "tiny")
    load_scene(folder)
    change(scene)
    scene.write(folder)
    again = load_scene(folder)
    assert len(loads) == 2
    assert_same_building(authors.load_authors_scene(folder), again)


def test_removed_optional_file_rebuilds(tmp_path: Path, cache_folder: Path, loads: list[Path]) -> None:
    folder = synthetic_scene().write(tmp_path / "tiny")
    assert load_scene(folder).initial_cells
    (folder / "initial_positions.yaml").unlink()
    assert load_scene(folder).initial_cells == [] and len(loads) == 2


def test_changed_map_gives_the_new_raster(tmp_path: Path, cache_folder: Path, loads: list[Path]) -> None:
    scene = synthetic_scene()
    folder = scene.write(tmp_path / "tiny")
    assert load_scene(folder).floors[0].cat_map[4, 4] == 0
    scene.cat_maps[0][4, 4] = -3  # a wall cell more
    scene.write(folder)
    assert load_scene(folder).floors[0].cat_map[4, 4] == -3
    assert len(loads) == 2


def test_off_switch_writes_and_reads_nothing(
    tmp_path: Path, cache_folder: Path, loads: list[Path], monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setenv(cache.OFF_ENV, "1")
    folder = synthetic_scene().write(tmp_path / "tiny")
    load_scene(folder)
    load_scene(folder)
    assert len(loads) == 2 and not cache_folder.exists()


def test_broken_entry_is_rebuilt_not_an_error(tmp_path: Path, cache_folder: Path, loads: list[Path]) -> None:
    folder = synthetic_scene().write(tmp_path / "tiny")
    load_scene(folder)
    (entry,) = cache_folder.glob(f"building-*{cache.SUFFIX}")
    entry.write_bytes(entry.read_bytes()[:100])  # truncated
    assert load_scene(folder).name == "Tiny"
    assert load_scene(folder).name == "Tiny"
    assert len(loads) == 2  # rebuilt once, then read


def test_scene_errors_still_come_from_the_loader(tmp_path: Path, cache_folder: Path) -> None:
    folder = synthetic_scene().write(tmp_path / "tiny")
    load_scene(folder)
    (folder / "cat_maps" / "0.png").unlink()
    with pytest.raises(authors.SceneError, match="does not exist"):
        load_scene(folder)


def test_folder_writable_by_others_is_not_used(
    tmp_path: Path, cache_folder: Path, loads: list[Path]
) -> None:
    cache_folder.mkdir(mode=0o700)
    cache_folder.chmod(0o777)
    folder = synthetic_scene().write(tmp_path / "tiny")
    load_scene(folder)
    load_scene(folder)
    assert len(loads) == 2 and not list(cache_folder.iterdir())


def test_grid_is_cached_per_building_content_and_radius(
    tmp_path: Path, cache_folder: Path, grid_builds: list[float]
) -> None:
    folder = synthetic_scene().write(tmp_path / "tiny")
    first = _grid(load_scene(folder), 0.1, grid_builds)
    second = _grid(load_scene(folder), 0.1, grid_builds)  # another process would see the same
    assert grid_builds == [0.1]
    assert np.array_equal(first.traversable, second.traversable) and first.stairs == second.stairs
    _grid(load_scene(folder), 0.0, grid_builds)
    assert grid_builds == [0.1, 0.0]


def test_grid_of_a_building_changed_in_memory_is_rebuilt(
    tmp_path: Path, cache_folder: Path, grid_builds: list[float]
) -> None:
    folder = synthetic_scene().write(tmp_path / "tiny")
    _grid(load_scene(folder), 0.1, grid_builds)
    changed = load_scene(folder)
    changed.floors[0].cat_map[3, 3] = -3  # a wall put in by the caller
    grid_of_changed = _grid(changed, 0.1, grid_builds)
    assert grid_builds == [0.1, 0.1] and not grid_of_changed.traversable[0, 3, 3]
    assert _grid(load_scene(folder), 0.1, grid_builds).traversable[0, 3, 3]  # the file's, still cached
    assert grid_builds == [0.1, 0.1]


def test_grid_of_a_building_made_in_code_is_cached_too(cache_folder: Path, grid_builds: list[float]) -> None:
    from sgplan.scene.demo import demo_building

    first = _grid(demo_building(), 0.0, grid_builds)
    second = _grid(demo_building(), 0.0, grid_builds)
    assert grid_builds == [0.0] and np.array_equal(first.traversable, second.traversable)


def test_prune_keeps_the_most_recently_used(tmp_path: Path) -> None:
    import os

    for age, name in enumerate(["old", "mid", "new"]):
        path = tmp_path / f"building-{name}{cache.SUFFIX}"
        path.write_bytes(b"x" * 100)
        os.utime(path, (1000 + age, 1000 + age))
    cache._prune(tmp_path, limit=250)
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"building-mid{cache.SUFFIX}",
                                                           f"building-new{cache.SUFFIX}"]


def test_content_hash_follows_the_contents_wherever_the_arrays_lie() -> None:
    import pickle

    base = {"name": "b", "maps": [np.arange(12, dtype=np.int32).reshape(3, 4), np.ones((2, 2), bool)],
            "fortran": np.asfortranarray(np.eye(3))}
    same = pickle.loads(pickle.dumps(base, protocol=5))  # equal contents, other objects
    assert cache.content_hash(same) == cache.content_hash(base) and len(cache.content_hash(base)) == 32
    changes = [("maps", 0, (2, 3), 99), ("maps", 1, (0, 0), False), ("fortran", None, (0, 1), 0.5)]
    for key, index, cell, value in changes:
        other = pickle.loads(pickle.dumps(base, protocol=5))
        array = other[key] if index is None else other[key][index]
        array[cell] = value
        assert cache.content_hash(other) != cache.content_hash(base), (key, index)
    strided = np.arange(20, dtype=np.int64)[::3]  # not contiguous: pickled in band, hashed all the same
    changed = strided.copy()[::1]
    changed[1] = 7
    assert cache.content_hash([strided]) == cache.content_hash([np.arange(20, dtype=np.int64)[::3]])
    assert cache.content_hash([strided]) != cache.content_hash([np.arange(20, dtype=np.int64)[::2]])
    assert cache.content_hash([changed]) != cache.content_hash([strided.copy()])
    swapped = dict(base, maps=[base["maps"][1], base["maps"][0]])  # the same bytes in another order
    assert cache.content_hash(swapped) != cache.content_hash(base)
    with pytest.raises((pickle.PicklingError, TypeError, AttributeError)):
        cache.content_hash({"f": lambda: 0})


def test_a_cached_scene_reports_the_callers_path_and_shares_its_grid(
    tmp_path: Path, cache_folder: Path, loads: list[Path], grid_builds: list[float],
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """`inspect` showed `gdata/Benevolence`, the path of whoever filled the cache, from another folder."""
    folder = synthetic_scene().write(tmp_path / "data" / "tiny")
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path)
    first = load_scene(Path("data/tiny"))
    monkeypatch.chdir(tmp_path / "elsewhere")
    second = load_scene(Path("../data/tiny"))
    assert len(loads) == 1  # one real load: the second came from the cache ...
    assert first.source == Path("data/tiny") and second.source == Path("../data/tiny")  # ... its own path
    assert second.source.resolve() == folder.resolve()
    _grid(first, 0.1, grid_builds)
    _grid(second, 0.1, grid_builds)
    assert grid_builds == [0.1] and second.source == Path("../data/tiny")  # one grid entry for both paths
