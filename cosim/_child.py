"""Child process that builds a cocotb model or runs one cocotb test module on it
(``cosim.build``).

Run as ``python -m irnuc.cosim._child SPEC.json``; it dies with its parent and takes the
simulator with it (``irnuc.common.process``).
"""

from __future__ import annotations

import json
import sys


def main(spec_path: str) -> int:
    from irnuc.common.process import die_with_parent

    die_with_parent()
    spec = json.loads(open(spec_path).read())
    from irnuc.cosim._cocotb_adapter import wheel_runner

    runner = wheel_runner(spec.get("visibility", "ports"))
    try:
        if "build" in spec:
            runner.build(**spec["build"])
        else:
            runner.build_dir = spec["build_dir"]
            runner.test(**spec["test"])
    except SystemExit as exc:  # the runner's way of saying the simulator failed
        return int(exc.code or 1) if isinstance(exc.code, int) else 1
    except RuntimeError as exc:  # a failed build command
        print(f"irnuc: {exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
