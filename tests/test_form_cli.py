"""`rostui publish` and `rostui call` refuse what they cannot open in one line, before any screen: a form file's
mistake with its file and line, a form of the other kind, an unknown type, a bad rate, no terminal."""

from __future__ import annotations

from pathlib import Path

import pytest

from cli_helpers import rostui


@pytest.mark.parametrize("args, says", [
    (["publish", "--form", "{bad}"], "ERROR: {bad}:5: std_msgs/String has no field 'nope' (it has data)"),
    (["call", "--form", "{bad}"], "ERROR: {bad}: a `publish` form: open it with `rostui publish --form {bad}`"),
    (["publish", "--form", "{other}"], "ERROR: {other}: a `call` form: open it with `rostui call --form {other}`"),
    (["publish", "--form", "{unknown}"], "ERROR: {unknown}: invalid message type: nope_msgs/Nope."),
    (["publish", "/a", "std_msgs/Nope"], "ERROR: invalid message type: std_msgs/Nope."),
    (["publish", "-r", "0"], "ERROR: --rate must be a positive number of Hz, not 0"),
    (["publish", "/a", "std_msgs/String"], "ERROR: rostui publish draws in a terminal: stdin and stdout must be a "
                                           "TTY (use `rostui topic pub` without one)"),
    (["call", "/a"], "ERROR: rostui call draws in a terminal: stdin and stdout must be a TTY (use `rostui service "
                     "call` without one)"),
])
def test_what_cannot_open_is_one_line(ros_env: dict[str, str], tmp_path: Path, args: list[str], says: str) -> None:
    files = {"bad": "publish: /a\ntype: std_msgs/String\nfields:\n  data: x\n  nope: 1\n",
             "other": "call: /spawn\n", "unknown": "publish: /a\ntype: nope_msgs/Nope\n"}
    paths = {name: tmp_path / f"{name}.yaml" for name in files}
    for name, text in files.items():
        paths[name].write_text(text)
    result = rostui([arg.format(**paths) for arg in args], ros_env)
    assert result.returncode == 1 and result.stdout == "", result
    assert result.stderr.startswith(says.format(**paths)) and result.stderr.count("\n") == 1, result.stderr


def test_a_form_file_not_written_yet_is_where_ctrl_w_will_save(ros_env: dict[str, str], tmp_path: Path) -> None:
    result = rostui(["publish", "/a", "std_msgs/String", "--form", str(tmp_path / "new.yaml")], ros_env)
    assert "draws in a terminal" in result.stderr and not (tmp_path / "new.yaml").exists()
