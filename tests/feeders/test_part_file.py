"""Specification of feeders.part_file: a part named or read from a YAML file (issue 39), and its
bad input as one line naming the file and field."""

from __future__ import annotations

import pytest
import yaml

from feeders.cup import cup_part
from feeders.fields import FieldError
from feeders.part import DEFAULT_PEG
from feeders.part_file import SHIPPED_PARTS, PartFileError, part_source


def test_a_shipped_name_gives_the_shipped_part_and_its_family_spec():
    assert part_source("cup").part == cup_part()
    assert part_source("cup").spec == "cup"
    assert part_source("peg").part == DEFAULT_PEG
    assert set(SHIPPED_PARTS) == {"peg", "cup"}


@pytest.mark.parametrize(
    "document",
    [
        {"part": {"outline": [[0, 0], [1, 0], [1, 1]], "density": 2.0}},  # as in a family
        {"outline": [[0, 0], [1, 0], [1, 1]], "density": 2.0},  # the part's own fields
        {"name": "x", "friction": 0.1, "part": {"outline": [[0, 0], [1, 0], [1, 1]],
                                                "density": 2.0}},  # any file with part:
    ],
)  # fmt: skip
def test_a_part_file_is_part_or_the_parts_own_fields(tmp_path, document):
    path = tmp_path / "tri.yaml"
    path.write_text(yaml.safe_dump(document))
    source = part_source(path)
    assert source.name == "tri"
    assert source.part.mass == pytest.approx(1.0, rel=1e-12)
    assert source.spec == document.get("part", document)


def test_a_shipped_family_file_serves_as_a_part_file():
    from feeders.device_family import packaged_family

    assert part_source(packaged_family("fig1-cup")).part == cup_part()


@pytest.mark.parametrize(
    ("content", "says"),
    [
        (None, "cannot read part file"),
        ("part:\n  outline: [[0, 0], [1, 0], [2, 0]]\n  density: 1\n", "zero area"),
        ("part:\n", "part: is empty"),
        ("friction: 0.1\n", "has no part: field"),
        ("part: {outline: [[0, 0], [1, 0], [1, 1]], density: 0}\n", "part.density = 0"),
        ("part: bowl\n", "not a packaged part"),
        ("- 1\n", "is not a part"),
        ("part: {heavy_fraction: 1.0}\n", "give part.heavy_fraction below 1"),
    ],
)
def test_a_bad_part_file_is_one_line_naming_the_file(tmp_path, content, says):
    path = tmp_path / "bad.yaml"
    if content is not None:
        path.write_text(content)
    with pytest.raises(PartFileError) as caught:
        part_source(path)
    message = str(caught.value)
    assert says in message and "bad.yaml" in message and "\n" not in message
    assert isinstance(caught.value, FieldError)  # the CLI's one line and exit 2


def test_an_unknown_name_lists_the_shipped_parts():
    with pytest.raises(PartFileError, match="neither a file nor a shipped part; shipped parts: "
                       "peg, cup"):  # fmt: skip
        part_source("bowl")
