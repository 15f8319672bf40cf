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


# issue 37, item 1: a config's family file is read by the one bounded reader
_FIG1 = (Path(__file__).parents[2] / "feeders" / "families" / "fig1.yaml").read_text()
_THETA = "theta: {low: 0.3, high: 0.9, default: 0.5}"
_HOSTILE_TEXTS = {  # each but the first three a family plain safe_load accepts
    "alias bomb": "a: &a [x, x, x, x, x, x, x, x, x]\n"
    + "".join(
        f"{c}: &{c} [{', '.join(['*' + p] * 9)}]\n"
        for p, c in zip("abcdefgh", "bcdefghi", strict=True)
    )
    + "parameters:\n  theta: *i\n",
    "long integer": "parameters: " + "7" * 5000 + "\n",
    "deep nesting": "parameters: " + "[" * 5000 + "]" * 5000 + "\n",
    "duplicate key": _FIG1 + "name: again\n",
    "tag": _FIG1.replace("name: fig1", "name: !!str fig1"),
    "merge key": _FIG1.replace(_THETA, "theta: {<<: {low: 0.3}, high: 0.9, default: 0.5}"),
    "octal": _FIG1.replace("name: fig1", "name: 017"),
}
assert all(_FIG1 != text for text in _HOSTILE_TEXTS.values())


@pytest.mark.parametrize("kind", sorted(_HOSTILE_TEXTS))
def test_a_family_text_is_refused_by_the_bounded_reader_in_one_line(
    kind: str, tmp_path: Path
) -> None:
    text = _HOSTILE_TEXTS[kind]
    (tmp_path / "hostile.yaml").write_text(text)
    with pytest.raises(_Refused) as caught:
        read_family_field("hostile.yaml", tmp_path, _Refused)
    message = str(caught.value)
    assert message.startswith("family: ") and "\n" not in message and len(message) < 1000
    with pytest.raises(FieldError) as again:  # a text stored in a database, read again
        family_of_text(text, "stored")
    assert "\n" not in str(again.value) and len(str(again.value)) < 1000


def test_a_family_file_too_big_not_text_or_not_a_file_is_refused_unread(tmp_path: Path) -> None:
    import os

    (tmp_path / "big.yaml").write_bytes(b"# " + b"x" * (2 << 20) + b"\n")
    (tmp_path / "latin1.yaml").write_bytes(b"name: caf\xe9\n")
    os.mkfifo(tmp_path / "fifo.yaml")
    for name, words in [
        ("big.yaml", "limit"),
        ("latin1.yaml", "not UTF-8"),
        ("fifo.yaml", "not a regular file|neither a file"),
    ]:
        with pytest.raises(_Refused, match=words):
            read_family_field(name, tmp_path, _Refused)
