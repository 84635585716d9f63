"""``python3 -m mjarm ARGS`` runs the mjarm command-line tool with ARGS (``mjarm --help``).

The tool is found at $MJARM_CLI, else where this package was built or installed from.
"""
import os
import sys


def cli_path() -> str:
    """Path of the mjarm CLI this package belongs to."""
    env = os.environ.get("MJARM_CLI")
    if env:
        return env
    from ._paths import CLI
    return CLI


def main() -> None:
    path = cli_path()
    if not os.access(path, os.X_OK):
        sys.stderr.write(f"python3 -m mjarm: the mjarm command-line tool is not at {path} "
                         "(build the mjarm_cli target, or set MJARM_CLI)\n")
        sys.exit(2)
    sys.stdout.flush()
    sys.stderr.flush()
    # the process becomes the CLI: its exit code, signals and terminal are the caller's
    os.execv(path, [path] + sys.argv[1:])


if __name__ == "__main__":
    main()
