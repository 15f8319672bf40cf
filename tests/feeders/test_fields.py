"""Reading YAML documents (scenes, configs) safely: every malformed file is one clear error,
found at once (issue 16: alias bombs, deep nesting, non-UTF-8 bytes, FIFOs, devices, huge
files used to end in MemoryError, RecursionError, UnicodeDecodeError or a hang)."""

from __future__ import annotations

import os
import threading
from pathlib import Path

import pytest

from feeders.fields import (
    MAX_DEPTH,
    MAX_DOCUMENT_BYTES,
    MAX_NAME,
    MAX_NODES,
    FieldError,
    mapping_field,
    name_field,
    number_field,
    read_yaml,
)

BILLION_LAUGHS = (
    'a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]\n'
    "b: &b [*a,*a,*a,*a,*a,*a,*a,*a,*a]\n"
    "c: &c [*b,*b,*b,*b,*b,*b,*b,*b,*b]\n"
    "d: &d [*c,*c,*c,*c,*c,*c,*c,*c,*c]\n"
    "e: &e [*d,*d,*d,*d,*d,*d,*d,*d,*d]\n"
    "f: &f [*e,*e,*e,*e,*e,*e,*e,*e,*e]\n"
    "g: &g [*f,*f,*f,*f,*f,*f,*f,*f,*f]\n"
)


def _read(path: Path) -> object:
    return read_yaml(path, "scene", FieldError)


def _error(path: Path) -> str:
    with pytest.raises(FieldError) as info:
        _read(path)
    message = str(info.value)
    assert "\n" not in message
    return message


def test_a_plain_document_reads_as_yaml_safe_load_would(tmp_path: Path) -> None:
    path = tmp_path / "ok.yaml"
    path.write_text("name: box\nbounds: [0, 1, 0, 1]\nnested: {a: [1, {b: 2}]}\n")
    assert _read(path) == {"name": "box", "bounds": [0, 1, 0, 1], "nested": {"a": [1, {"b": 2}]}}


def test_an_alias_bomb_is_refused_at_its_first_alias(tmp_path: Path) -> None:
    path = tmp_path / "bomb.yaml"
    path.write_text(BILLION_LAUGHS)
    assert "aliases" in _error(path) and "line 2" in _error(path)


def test_nesting_beyond_the_limit_is_refused_and_within_it_reads(tmp_path: Path) -> None:
    deep = tmp_path / "deep.yaml"
    deep.write_text("[" * 1000 + "]" * 1000)
    assert f"deeper than {MAX_DEPTH}" in _error(deep)
    fine = tmp_path / "fine.yaml"  # a mapping holding lists MAX_DEPTH deep in all
    fine.write_text("a: " + "[" * (MAX_DEPTH - 1) + "]" * (MAX_DEPTH - 1))
    assert _read(fine) is not None


def test_non_utf8_bytes_name_the_byte(tmp_path: Path) -> None:
    path = tmp_path / "latin1.yaml"
    path.write_bytes(b"name: caf\xe9\n")
    assert "not UTF-8" in _error(path) and "0xe9" in _error(path)


def test_a_file_over_the_size_limit_is_refused_without_reading_it(tmp_path: Path) -> None:
    path = tmp_path / "big.yaml"
    with path.open("wb") as handle:
        handle.truncate(MAX_DOCUMENT_BYTES + 1)  # sparse: the check must come from the size
    assert "limit" in _error(path)


def test_a_fifo_nobody_writes_is_refused_at_once(tmp_path: Path) -> None:
    """Opening a FIFO blocks until a writer comes; the reader must not open it at all. Run in
    a thread so that a regression fails the test instead of hanging the suite."""
    path = tmp_path / "pipe.yaml"
    os.mkfifo(path)
    result: list[str] = []
    worker = threading.Thread(target=lambda: result.append(_error(path)), daemon=True)
    worker.start()
    worker.join(timeout=300)  # a hang guard: the refusal is at once
    if worker.is_alive():  # unblock the reader, then fail
        with open(path, "w"):
            pass
        pytest.fail("reading a FIFO blocked")
    assert "not a regular file" in result[0]


@pytest.mark.parametrize("path", ["/dev/zero", "/proc"])
def test_devices_and_directories_are_not_regular_files(path: str) -> None:
    assert "not a regular file" in _error(Path(path))


def test_a_missing_file_and_an_overlong_name_are_one_line_errors(tmp_path: Path) -> None:
    assert "No such file" in _error(tmp_path / "missing.yaml")
    assert "cannot read" in _error(tmp_path / ("x" * 5000 + ".yaml"))


def test_a_dense_list_within_the_byte_limit_is_refused_by_its_node_count(tmp_path: Path) -> None:
    """400,000 numbers in 800 kB: under the byte limit, but PyYAML's pure-Python loader took
    ~20 s to build them. The event scan stops at MAX_NODES."""
    path = tmp_path / "dense.yaml"
    path.write_text("[" + ",".join(["1"] * 400_000) + "]")
    assert path.stat().st_size <= MAX_DOCUMENT_BYTES
    assert f"more than {MAX_NODES} values" in _error(path)
    fine = tmp_path / "fine.yaml"  # the mapping, its key and the list are 3 of the nodes
    fine.write_text("a: [" + ",".join(["1"] * (MAX_NODES - 3)) + "]")
    assert _read(fine) == {"a": [1] * (MAX_NODES - 3)}


def test_an_integer_too_long_to_convert_is_one_line(tmp_path: Path) -> None:
    path = tmp_path / "digits.yaml"
    path.write_text("count: " + "9" * 5000 + "\n")
    assert "4300 digits" in _error(path)


def test_a_long_path_is_shortened_in_the_message(tmp_path: Path) -> None:
    message = _error(tmp_path / ("x" * 5000 + ".yaml"))
    assert len(message) < 300 and "characters)" in message


@pytest.mark.parametrize(
    ("value", "allowed"),
    [(10**400, False), (-(10**400), False), (1e308, False), (2.5, True), (3, True)],
)
def test_number_field_refuses_integers_beyond_floats_as_out_of_range(value, allowed) -> None:
    """float(10**400) raises OverflowError; it must be an out-of-range FieldError."""
    if allowed:
        assert number_field(value, "x", 0.0, 10.0) == float(value)
        return
    with pytest.raises(FieldError, match=r"x = -?inf is outside|x = 1e\+308 is outside"):
        number_field(value, "x", 0.0, 10.0)


@pytest.mark.parametrize(
    "value",
    [
        "",
        "x" * (MAX_NAME + 1),
        "a/b",
        "..",
        ".",
        "a\nb",
        "tab\there",
        None,
        [1],
        True,
        "next\u0085line",  # C1 control NEL (issue 23: OMPL's log reader split on it at export)
        "line\u2028separator",
        "para\u2029graph",
        "c1\x9fcontrol",
    ],
)
def test_names_that_cannot_be_part_of_a_file_name_are_refused(value) -> None:
    with pytest.raises(FieldError) as info:
        name_field(value)
    assert str(info.value).startswith("name") and "\n" not in str(info.value)


@pytest.mark.parametrize("value", ["default", "my sweep", "a.b-c_d", "x" * MAX_NAME, 7])
def test_ordinary_names_are_kept(value) -> None:
    assert name_field(value) == str(value)


def test_mapping_keys_of_mixed_types_are_listed_not_compared() -> None:
    """sorted() of {1, 'a'} raises TypeError; the unknown keys are named as text."""
    with pytest.raises(FieldError, match=r"unknown key\(s\) \['1', 'b'\]"):
        mapping_field({1: 0, "b": 0, "a": 0}, "doc", {"a"})


@pytest.mark.parametrize(
    "text, line",
    [
        ("designs: {count: 8}\nseed: 0\ndesigns: {count: 1000000}\n", 3),
        ("ladder:\n  - level: geometric\n    budget: {time: 1, time: 2}\n", 3),
    ],
)
def test_a_repeated_key_is_refused_naming_it_and_its_line(
    tmp_path: Path, text: str, line: int
) -> None:
    """Issue 23: a duplicate key was accepted, the last one winning (a repeated ``designs``
    block with count 10^6 hung a sweep); the project's rule is a safe loader that refuses
    duplicate keys."""
    path = tmp_path / "dup.yaml"
    path.write_text(text)
    message = _error(path)
    assert "repeated key" in message and f"line {line}" in message


@pytest.mark.parametrize(
    "value, what",
    [
        ("1:30", "sexagesimal"),
        ("-2:05:30.5", "sexagesimal"),
        ("017", "leading zero"),
        ("+0_17", "leading zero"),
    ],
)
def test_yaml_1_1_numbers_that_surprise_are_refused(tmp_path: Path, value: str, what: str) -> None:
    """Issue 23: YAML 1.1 reads ``count: 1:30`` as 90 (base 60) and ``017`` as 15 (octal)."""
    path = tmp_path / "num.yaml"
    path.write_text(f"count: {value}\n")
    message = _error(path)
    assert what in message and "line 1" in message


@pytest.mark.parametrize("text", ["name: !!float 1000\n", "bounds: !!python/tuple [0, 1]\n"])
def test_explicit_tags_are_refused(tmp_path: Path, text: str) -> None:
    """Issue 23: ``!!float`` turned a name into "1000.0"; no scene or config needs a tag."""
    path = tmp_path / "tag.yaml"
    path.write_text(text)
    assert "tag" in _error(path)


def test_quoted_and_ordinary_numbers_still_read(tmp_path: Path) -> None:
    path = tmp_path / "ok.yaml"
    path.write_text("a: '1:30'\nb: \"017\"\nc: 0\nd: 0.5\ne: 10\nf: 1e-3\ng: -0.25\nh: 1_000\n")
    assert _read(path) == {
        "a": "1:30",
        "b": "017",
        "c": 0,
        "d": 0.5,
        "e": 10,
        "f": "1e-3",
        "g": -0.25,
        "h": 1000,
    }


@pytest.mark.parametrize(
    "text, what",
    [
        ("root:x:0:0:root:/root:/bin/bash\ndaemon:x:1:1:secret\n", "text"),
        ("just some words\nsecond line secret\n", "text"),
        ("- secret\n- 2\n", "a list"),
        ("", "empty"),
        ("42\n", "a number"),
    ],
)
def test_a_file_that_is_not_a_mapping_is_named_without_echoing_it(
    tmp_path: Path, text: str, what: str
) -> None:
    """Issue 23: a config that is /etc/passwd (or any non-YAML text) had its first lines
    echoed in the error. The file is named and what its document is, never its content."""
    path = tmp_path / "not-a-scene"
    path.write_text(text)
    message = _error(path)
    assert "secret" not in message and "root:x" not in message
    assert "not-a-scene" in message and what in message and "mapping" in message


# Lines of a shadow file and other text that is not YAML; "SECRET" marks what must never be
# quoted in an error. Each breaks the parse (or a rule of ours) at a known line.
SECRET_TEXTS = [
    (
        "root:$6$SECRETsalt$SECREThash:19000:0:99999:7:::\nuser:\t$6$SECRET2: 19000:0:99999:7:::\n",
        2,
    ),
    ("root:$6$SECRETsalt:19000:0:99999:7:::\n\tSECRETtab: 1\n", 2),
    ("SECRETkey: 1\nSECRETkey: 2\n", 2),  # a repeated key
    ("a: 1\nb: !SECRETtag x\n", 2),  # an explicit local tag
    ("a: !!SECRETtag x\n", 1),  # an explicit tag of YAML's own namespace
    ("a: !SECRET!x 1\n", 1),  # an undefined tag handle
    ('a: "\\qSECRETescape"\n', 1),  # an unknown escape
    ("%YAML 1.1 SECRETdirective\na: 1\n", 1),
    ("a: &SECRET# 1\n", 1),  # a bad anchor
    ("a: 1\nb: SECRET: x: y\n", 2),
    ("a: 12:30:45\n", 1),  # base 60 in YAML 1.1 (the value is the file's text too)
    ("a: 0755\n", 1),  # octal in YAML 1.1
]


@pytest.mark.parametrize("parser", ["libyaml", "python"])
@pytest.mark.parametrize(("text", "line"), SECRET_TEXTS)
def test_a_file_that_is_not_yaml_is_named_with_its_line_never_quoted(
    tmp_path: Path, monkeypatch, parser: str, text: str, line: int
) -> None:
    """Issue 23: a config that is /etc/shadow (or any non-YAML text) had its text in the error
    (PyYAML's problem quotes the token it stopped at; ours quoted a repeated key or a tag).
    The error names the file and the line, never a character of its content; with PyYAML's
    pure-Python parser too (used where PyYAML was built without libyaml)."""
    import yaml

    if parser == "python":
        monkeypatch.setattr("feeders.fields._PARSER", yaml.SafeLoader)
    elif not yaml.__with_libyaml__:
        pytest.skip("PyYAML without libyaml")
    path = tmp_path / "shadow"
    path.write_text(text)
    message = _error(path)
    assert "/shadow' is not valid YAML" in message and f"(line {line}, column" in message
    said = message.split("is not valid YAML")[1]  # after the file's name
    for secret in ("SECRET", "root", "$6$", "19000", "12:30", "0755", "\\t", "'#'", "'q'"):
        assert secret not in said, message


@pytest.mark.parametrize("value", [" lead", "trail ", "\u00a0nbsp", "en\u2002", "  ", "\u3000wide"])
def test_a_name_with_space_at_either_end_is_refused_not_changed(value: str) -> None:
    """Issue 23: a config name with a leading space was silently stripped on its way to OMPL's
    database (its log reader strips the experiment name), so names differed from what the user
    wrote. A name that begins or ends with white space is refused, naming the field."""
    with pytest.raises(FieldError) as info:
        name_field(value, "obstacles[0].label")
    message = str(info.value)
    assert message.startswith("obstacles[0].label") and "white space" in message
    assert "\n" not in message


def test_space_inside_a_name_is_kept() -> None:
    assert name_field("my  sweep 2") == "my  sweep 2"
