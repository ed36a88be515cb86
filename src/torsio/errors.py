"""Exceptions raised by torsio.

Every error names the offending key or value and says what was expected, so a
message can be shown to a user as it is (the CLI prints it and exits non-zero).
"""

from __future__ import annotations


class TorsioError(Exception):
    """Base class of every error torsio raises on purpose."""


class ConfigError(TorsioError, ValueError):
    """Invalid input: a configuration key, a parameter value or a unit.

    Parameters
    ----------
    key : str
        Dotted path of the offending key, e.g. ``"section[2].od"``.
    message : str
        What is wrong and what was expected.
    """

    def __init__(self, key: str, message: str) -> None:
        self.key = key
        self.message = message
        super().__init__(f"{key}: {message}" if key else message)


class SolverError(TorsioError, RuntimeError):
    """A numerical solver failed or produced non-finite values."""


class PluginError(TorsioError):
    """A plugin is broken or conflicts with another one."""


class OutputError(TorsioError, OSError):
    """A file could not be written (a full disk, a quota, an I/O error); nothing was left
    in its place (:mod:`torsio.output_files`).

    Parameters
    ----------
    path : str or path-like
        The file that was being written.
    reason : str
        The operating system's reason (``"No space left on device"``).
    """

    def __init__(self, path: object, reason: str) -> None:
        self.path = str(path)
        self.reason = reason
        super().__init__(f"cannot write {self.path!r}: {reason}")

    def __str__(self) -> str:
        return str(self.args[0])
