"""Run a command so that its whole process group dies with the irnuc process that started
it: ``python -m irnuc.common._reaper CMD [ARGS...]`` (used by ``process.run_child``).

The reaper is the leader of the group the command runs in; when its parent dies it gets
SIGTERM (``PR_SET_PDEATHSIG``) and kills the group, so a tool that starts tools of its own
(``make`` and the compilers it runs) leaves nothing behind. Its exit status is the
command's (128 + signal number when a signal ended it).
"""

from __future__ import annotations

import subprocess
import sys


def main(argv: list[str]) -> int:
    from irnuc.common.process import die_with_parent

    die_with_parent()
    try:
        proc = subprocess.Popen(argv)
    except OSError as exc:
        print(f"irnuc: cannot run {argv[0]}: {exc.strerror}", file=sys.stderr)
        return 127
    code = proc.wait()
    return 128 - code if code < 0 else code


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
