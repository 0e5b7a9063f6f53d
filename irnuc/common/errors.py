"""The error classes every layer raises, so the command line can tell them apart.

* :class:`UserError` (a ``ValueError``): bad input the user can fix: an argument, a
  value, a file, a configuration field. The command line prints its message as one line
  and exits with status 2. Messages name the flag, file or dotted field and what is
  allowed. :class:`ConfigError` is the one for a configuration field (sensor, pipeline,
  report): every layer raises this same class.
* :class:`ToolError` (a ``RuntimeError``): an external tool (Verilator, the C++
  compiler, Yosys, nextpnr) failed; the message names the log. Exit status 3.
* :class:`StreamError` (a :class:`UserError`): stdout cannot be written (``| head``,
  ``> /dev/full``); one line naming the stream, exit status 2.
* Anything else is a bug in irnuc and keeps its traceback.
"""

from __future__ import annotations


class IrnucError(Exception):
    """Base class of the errors irnuc raises on purpose."""


class UserError(IrnucError, ValueError):
    """A user-caused error: printed as one line, exit status 2."""


class ConfigError(UserError):
    """A configuration field (sensor, pipeline, report) is missing, unknown or outside its
    legal range; the message names the dotted field, the value and what is allowed."""


class ToolError(IrnucError, RuntimeError):
    """An external tool failed: printed as one line naming its log, exit status 3."""


class StreamError(UserError):
    """A standard stream cannot be written (a closed pipe, a full disk): printed as one
    line naming the stream, exit status 2. Outputs under ``--out`` stay whole: each is
    replaced only as a unit."""
