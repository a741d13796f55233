"""Every option of the eqhb commands has a Python counterpart (parity.json):
the test reads each command's --help, so an option added to the command
without a Python entry fails here, as does an entry naming a parameter that
the Python function does not have."""
import inspect
import json
import os
import pathlib
import re
import subprocess

import pytest

import eqhb

TABLE = json.loads((pathlib.Path(__file__).parent / "parity.json").read_text())
COMMANDS = sorted(TABLE["commands"])


def cli():
    path = os.environ.get("EQHB_CLI")
    if not path:
        pytest.skip("EQHB_CLI is not set: built without the eqhb command (tests/CMakeLists.txt sets it)")
    return path


def help_options(command):
    """The options `eqhb COMMAND --help` lists: each positional and each --flag."""
    text = subprocess.run([cli(), command, "--help"], capture_output=True, text=True, check=True).stdout
    options = set()
    section = None
    for line in text.splitlines():
        if re.match(r"^\S.*:\s*$", line):
            section = line.strip().rstrip(":")
        elif re.match(r"^  \S", line):
            first = line.split()[0]
            if section == "Positionals":
                options.add(first)
            elif section == "Options":
                options.update(name for name in first.split(",") if name.startswith("--"))
    return options


def parameters(function_name):
    return set(inspect.signature(getattr(eqhb, function_name)).parameters)


@pytest.mark.parametrize("command", COMMANDS)
def test_every_cli_option_has_a_python_entry(command):
    listed = help_options(command)
    assert "--omega" in listed and "scene" in listed, f"could not read `eqhb {command} --help`: {listed}"
    missing = sorted(listed - set(TABLE["commands"][command]["options"]))
    assert not missing, f"eqhb {command}: options without a Python entry in parity.json: {missing}"


@pytest.mark.parametrize("command", COMMANDS)
def test_every_entry_names_an_existing_python_parameter(command):
    entry = TABLE["commands"][command]
    for option, counterpart in entry["options"].items():
        if isinstance(counterpart, str):
            function, parameter = entry["function"], counterpart
        elif "not_applicable" in counterpart:
            assert counterpart["not_applicable"], f"{command} {option}: say why no counterpart is needed"
            continue
        else:
            function, parameter = counterpart.get("function", entry["function"]), counterpart["parameter"]
        assert parameter in parameters(function), f"{command} {option}: eqhb.{function} has no parameter {parameter}"


@pytest.mark.parametrize("command", COMMANDS)
def test_no_entry_is_left_over_from_a_removed_option(command):
    stale = sorted(set(TABLE["commands"][command]["options"]) - help_options(command))
    assert not stale, f"eqhb {command}: parity.json lists options the command no longer has: {stale}"
