"""A config's ``family:`` field, shared by the sweep and the optimiser (issue 24)."""

from __future__ import annotations

from pathlib import Path

import pytest

from experiments.family_config import (
    family_file,
    family_of_text,
    family_record,
    read_family_field,
    text_digest,
)
from feeders.device_family import packaged_families
from feeders.fields import FieldError


class _Refused(FieldError):
    pass


def test_packaged_families_are_found_by_name_with_or_without_suffix(tmp_path: Path) -> None:
    assert {"fig1", "fig1-cup"} <= set(packaged_families())
    by_name = family_file("fig1-cup", tmp_path)
    assert by_name is not None and by_name.name == "fig1-cup.yaml"
    assert family_file("fig1-cup.yaml", tmp_path) == by_name
    assert family_file("no-such-family", tmp_path) is None


def test_a_file_is_found_relative_to_the_config_folder_before_a_packaged_name(
    tmp_path: Path,
) -> None:
    packaged = family_file("fig1", tmp_path)
    assert packaged is not None
    (tmp_path / "fig1").write_text(packaged.read_text())
    assert family_file("fig1", tmp_path) == (tmp_path / "fig1").resolve()


def test_the_field_reads_path_text_and_family_and_refuses_in_one_line(tmp_path: Path) -> None:
    path, text, family = read_family_field("fig1-cup", tmp_path, _Refused)
    assert Path(path).is_absolute() and text == Path(path).read_text()
    assert (
        family.name == "fig1-cup" and family.vector_names == family_of_text(text, "x").vector_names
    )
    with pytest.raises(_Refused, match=r"^family = 'nowhere' is neither a file .*fig1-cup"):
        read_family_field("nowhere", tmp_path, _Refused)
    with pytest.raises(_Refused, match=r"^family = 3; allowed: a packaged family's name"):
        read_family_field(3, tmp_path, _Refused)
    (tmp_path / "bad.yaml").write_text("parameters: {}\n")
    with pytest.raises(_Refused) as caught:
        read_family_field("bad.yaml", tmp_path, _Refused)
    assert str(caught.value).startswith("family: ") and "\n" not in str(caught.value)


def test_the_record_rebuilds_the_same_family_and_the_digest_follows_the_text(
    tmp_path: Path,
) -> None:
    _, text, family = read_family_field("fig1-cup", tmp_path, _Refused)
    record = family_record(family, text)
    assert record["parameters"] == list(family.vector_names)
    assert record["entries"] == [name for name, _ in family.entries]
    again = family_of_text(record["yaml"], record["name"])
    assert again.vector_names == family.vector_names and list(again.default()) == list(
        family.default()
    )
    assert text_digest(text) != text_digest(text + "\n# a comment\n")
