"""``python -m mjarm ARGS`` runs the mjarm command-line tool with ARGS (``mjarm --help``).

The tool is found at $MJARM_CLI, else where this package was built or installed with it: the
build tree's CLI, or the installed one, whose path is relative to this package (a wheel's is
``mjarm/bin/mjarm``). The wheel's console script ``mjarm`` is :func:`main`.
"""
import os
import sys


def cli_path() -> str:
    """Path of the mjarm CLI this package belongs to."""
    env = os.environ.get("MJARM_CLI")
    if env:
        return env
    from ._paths import CLI
    # an absolute CLI (a build tree's) is kept as it is by join
    return os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), CLI))


def main() -> None:
    path = cli_path()
    if not os.access(path, os.X_OK):
        sys.stderr.write(f"python -m mjarm: the mjarm command-line tool is not at {path} "
                         "(build the mjarm_cli target, reinstall the package, or set MJARM_CLI)\n")
        sys.exit(2)
    sys.stdout.flush()
    sys.stderr.flush()
    # the process becomes the CLI: its exit code, signals and terminal are the caller's
    os.execv(path, [path] + sys.argv[1:])


if __name__ == "__main__":
    main()
