"""What a Hops request may reach: templates by name (shipped, or in the
server's folder), never a path; Host and Origin headers of the server's own."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from onefold_cad.errors import InvalidParameterError
from onefold_cad.hops.guard import allowed_hosts, request_problem, resolve_template
from onefold_cad.templates import find_template


def test_a_shipped_name_is_its_file():
    assert Path(resolve_template("paper-square", None)) == find_template("paper-square")
    assert Path(resolve_template("paper-square.toml", None)) == find_template("paper-square")


def _refusal(ref: str, folder: Path | None) -> str:
    with pytest.raises(InvalidParameterError) as info:
        resolve_template(ref, folder)
    assert info.value.parameter == "template"
    return str(info.value)


def test_a_path_is_refused_whether_or_not_the_file_exists(tmp_path):
    secret = tmp_path / "secret.toml"
    secret.write_text('[frame]\nalpha = "the secret"\n')
    shipped = find_template("paper-square")
    for ref in (str(secret), str(shipped), "/etc/shadow", "../templates/paper-square.toml",
                str(tmp_path / "missing.toml"), "/etc/passwd"):  # fmt: skip
        message = _refusal(ref, None)
        assert "the secret" not in message
        assert "no template named" in message and "TOML" not in message

    # the same words for a file that exists and one that does not: only the name shown differs
    def words(ref: str) -> str:
        shown = ref if len(ref) <= 80 else ref[:77] + "..."
        return _refusal(ref, None).replace(repr(shown), "X")

    assert words(str(secret)) == words(str(tmp_path / "missing.toml"))


def test_the_server_s_folder_gives_its_templates_by_name_only(tmp_path):
    folder = tmp_path / "mine"
    folder.mkdir()
    shutil.copy(find_template("paper-square"), folder / "my-fold.toml")
    shutil.copy(find_template("paper-square"), folder / "site-x.toml")  # a site file: not a design
    (folder / "sub").mkdir()
    shutil.copy(find_template("paper-square"), folder / "sub" / "deep.toml")
    outside = tmp_path / "outside.toml"
    shutil.copy(find_template("paper-square"), outside)
    assert resolve_template("my-fold", folder) == str(folder / "my-fold.toml")
    assert resolve_template("my-fold.toml", folder) == str(folder / "my-fold.toml")
    assert resolve_template("table1-row1", folder) == str(find_template("table1-row1"))
    for ref in ("site-x", "sub/deep", "deep", "../outside", str(outside),
                str(folder / "my-fold.toml")):  # fmt: skip
        assert "no template named" in _refusal(ref, folder)
    assert "my-fold" in _refusal("nothing", folder)  # the names it takes are listed


def test_a_folder_template_comes_before_a_shipped_one_of_its_name(tmp_path):
    shutil.copy(find_template("table1-row1"), tmp_path / "paper-square.toml")
    assert resolve_template("paper-square", tmp_path) == str(tmp_path / "paper-square.toml")


def test_a_long_name_is_shown_cut():
    message = _refusal("x" * 5000, None)
    assert len(message) < 1000


@pytest.mark.parametrize(
    ("host", "port", "extra", "allowed", "refused"),
    [
        ("127.0.0.1", 5000, (), {"127.0.0.1:5000", "localhost:5000", "[::1]:5000"},
         {"evil.example:5000", "127.0.0.1:5001", "", "127.0.0.1"}),
        ("0.0.0.0", 80, ("Studio-PC",), {"0.0.0.0:80", "studio-pc:80"},
         {"localhost:80", "evil.example:80"}),
        ("192.168.1.20", 5000, (), {"192.168.1.20:5000"}, {"localhost:5000"}),
        ("::1", 5000, (), {"[::1]:5000", "localhost:5000"}, {"::1:5000"}),
    ],
)  # fmt: skip
def test_allowed_hosts(host, port, extra, allowed, refused):
    hosts = allowed_hosts(host, port, extra)
    assert allowed <= hosts
    assert not (refused & hosts)


@pytest.mark.parametrize(
    ("headers", "refused"),
    [
        ({"Host": "127.0.0.1:5000"}, False),  # Hops: no Origin
        ({"Host": "LOCALHOST:5000"}, False),
        ({"Host": "127.0.0.1:5000", "Origin": "http://127.0.0.1:5000"}, False),
        ({"Host": "127.0.0.1:5000", "Sec-Fetch-Site": "same-origin"}, False),
        ({}, True),
        ({"Host": "rebound.example:5000"}, True),  # DNS rebinding
        ({"Host": "127.0.0.1:5000", "Origin": "https://evil.example"}, True),
        ({"Host": "127.0.0.1:5000", "Origin": "null"}, True),
        ({"Host": "127.0.0.1:5000", "Sec-Fetch-Site": "cross-site"}, True),
        ({"Host": "127.0.0.1:5000", "Sec-Fetch-Site": "same-site"}, True),
    ],
)
def test_request_problem(headers, refused):
    problem = request_problem(headers, allowed_hosts("127.0.0.1", 5000))
    assert (problem is not None) == refused
    if refused:
        assert problem.startswith("forbidden: ") and "\n" not in problem
