"""`pip install .` checked end to end: the PEP 517 backend (pyproject.toml) builds a wheel from
the source tree, pip installs it into a fresh virtual environment, and everything is used from
there with the source tree out of reach (no PYTHONPATH, no MJARM_* variables, another working
folder): the package imports, loads a bundled model and solves an IK; `python -m mjarm` and the
console script `mjarm` run the CLI inside the package; the models are the package's; the
binaries' run paths lead to the environment's mujoco, and one libmujoco is loaded; where node and
npm are found, the wheel holds the replay page and writes one from the CLI and from Python.

Usage: wheel_check.py SOURCE_DIR WORK_DIR [--compiler CXX | --like BUILD [--preload LIBS] |
                                            --isolated]

By default the build runs without pip's build isolation, in WORK_DIR/build-env: a virtual
environment holding exactly the build requirements of pyproject.toml (what isolation would
install), with a build folder kept between runs (scikit-build-core's build-dir), so a second run
recompiles only what changed; isolation's temporary paths would make every run a full build. It
compiles with CXX (c++ when not given: GCC on Debian, what `pip install .` uses) and -Werror,
unoptimized (-O0, and GCC collects its garbage rarely): what is checked is the package, not the
speed of its code (`make check-gcc` passes g++).
--like BUILD compiles as the build folder BUILD does (its compiler, flags, sanitizers, compiler
launcher), in the environment of its interpreter (MJARM_PYTHON_EXECUTABLE: the project's .venv,
which holds the build requirements at their pins), in the folder BUILD-wheel beside it: so a
compiler cache (make test's ccache) gives it BUILD's objects instead of a second compile. A
sanitized wheel's binaries also run from the sanitizer runtime's folder, and the Python that
uses them gets LIBS (colon-separated: the runtime first) preloaded, as make test's Python suite.
--isolated builds exactly as `pip install .` does: isolated, Release, in a temporary build folder.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import time
import tomllib
import zipfile
from pathlib import Path

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print(f"FAILED: {what}", flush=True)


def run(command, **kwargs):
    """Runs a command, printing it and its wall time; its failure ends the check."""
    started = time.monotonic()
    print("$", " ".join(str(c) for c in command), flush=True)
    result = subprocess.run([str(c) for c in command], text=True, capture_output=True, **kwargs)
    print(f"  ({time.monotonic() - started:.1f} s)", flush=True)
    if result.returncode != 0:
        sys.exit(f"failed ({result.returncode}): {' '.join(map(str, command))}\n"
                 f"{result.stdout}\n{result.stderr}")
    return result.stdout


def make_venv(path, with_pip=True):
    shutil.rmtree(path, ignore_errors=True)
    # a venv made from inside a venv stands on the base interpreter, as scripts/setup_venv.sh's
    run([sys.executable, "-m", "venv", *([] if with_pip else ["--without-pip"]), path])
    return path / "bin" / "python"


PIP = ["-m", "pip", "--disable-pip-version-check", "--no-input"]


def cache_entries(build):
    """The entries of a build folder's CMakeCache.txt, by name."""
    entries = {}
    for line in (build / "CMakeCache.txt").read_text().splitlines():
        m = re.match(r"([A-Za-z_][A-Za-z0-9_]*):[A-Z]+=(.*)", line)
        if m:
            entries[m.group(1)] = m.group(2)
    return entries


def build_like(build, source, dist, requires):
    """Builds the wheel into `dist` as the build folder `build` compiles (--like)."""
    cache = cache_entries(build)
    builder = Path(cache["MJARM_PYTHON_EXECUTABLE"])
    pins = dict(r.split("==") for r in requires)
    installed = run([builder, "-c", "import importlib.metadata as m, sys; "
                     "print(' '.join(m.version(n) for n in sys.argv[1:]))", *pins]).split()
    for (name, pin), version in zip(pins.items(), installed):
        check(version == pin, f"{builder} has {name} {version}, pyproject.toml builds with {pin}")
    if failures:
        sys.exit("the build environment is not pyproject.toml's (run scripts/setup_venv.sh)")
    build_type = cache["CMAKE_BUILD_TYPE"]
    defines = {"CMAKE_BUILD_TYPE": build_type,
               f"CMAKE_CXX_FLAGS_{build_type.upper()}":
                   cache.get(f"CMAKE_CXX_FLAGS_{build_type.upper()}", "")}
    for name in ["CMAKE_CXX_COMPILER", "CMAKE_CXX_COMPILER_LAUNCHER", "MJARM_SANITIZE",
                 "MJARM_UNITY_BUILD", "MJARM_WERROR", "MJARM_GCC_COLLECT_RARELY",
                 "CMAKE_EXE_LINKER_FLAGS", "CMAKE_MODULE_LINKER_FLAGS"]:
        if cache.get(name):
            defines[name] = cache[name]
    # the objects come from the compiler cache; the two links (the extension, the CLI) do not,
    # and are most of the build's CPU: gold links them in half of ld's time, where BUILD names
    # no linker of its own
    if shutil.which("ld.gold") and not any("-fuse-ld" in defines.get(f"CMAKE_{kind}_LINKER_FLAGS", "")
                                           for kind in ("EXE", "MODULE")):
        for kind in ("EXE", "MODULE"):
            flags = defines.get(f"CMAKE_{kind}_LINKER_FLAGS", "")
            defines[f"CMAKE_{kind}_LINKER_FLAGS"] = (flags + " -fuse-ld=gold").strip()
    run([builder, *PIP, "wheel", "--no-build-isolation", "--no-deps", "-q", "-w", dist,
         f"--config-settings=build-dir={build}-wheel",
         *(f"--config-settings=cmake.define.{k}={v}" for k, v in defines.items()), source],
        env={**os.environ, "CMAKE_GENERATOR": cache["CMAKE_GENERATOR"]})


def main():
    source, work = Path(sys.argv[1]).resolve(), Path(sys.argv[2]).resolve()
    options = sys.argv[3:]
    isolated = "--isolated" in options

    def option(name, default=None):
        return options[options.index(name) + 1] if name in options else default

    compiler, like = option("--compiler", "c++"), option("--like")
    preload = [lib for lib in option("--preload", "").split(":") if lib]
    work.mkdir(parents=True, exist_ok=True)
    pyproject = tomllib.loads((source / "pyproject.toml").read_text())
    version = re.search(r"project\(mjarm VERSION ([0-9.]+)",
                        (source / "CMakeLists.txt").read_text()).group(1)
    mujoco_pin = next(d for d in pyproject["project"]["dependencies"] if d.startswith("mujoco=="))
    mujoco_version = mujoco_pin.split("==")[1]

    dist = work / "dist"
    shutil.rmtree(dist, ignore_errors=True)
    if isolated:
        builder = make_venv(work / "isolated-env")
        run([builder, *PIP, "wheel", "--no-deps", "-q", "-w", dist, source])
    elif like:
        build_like(Path(like).resolve(), source, dist, pyproject["build-system"]["requires"])
    else:
        builder = work / "build-env" / "bin" / "python"
        requires = pyproject["build-system"]["requires"]
        stamp = work / "build-env" / ".requires"
        if not (builder.exists() and stamp.exists() and stamp.read_text() == repr(requires)):
            make_venv(work / "build-env")
            run([builder, *PIP, "install", "-q", *requires])
            stamp.write_text(repr(requires))
        run([builder, *PIP, "wheel", "--no-build-isolation", "--no-deps", "-q", "-w", dist,
             "--config-settings=build-dir=" + str(work / "cmake-build"),
             "--config-settings=cmake.build-type=Debug",
             "--config-settings=cmake.define.CMAKE_CXX_FLAGS_DEBUG=-O0",
             "--config-settings=cmake.define.MJARM_GCC_COLLECT_RARELY=ON",
             "--config-settings=cmake.define.MJARM_UNITY_BUILD=ON",
             "--config-settings=cmake.define.CMAKE_CXX_COMPILER=" + compiler,
             "--config-settings=cmake.define.MJARM_WERROR=ON", source])
    wheels = list(dist.glob("mjarm-*.whl"))
    check(len(wheels) == 1, f"one wheel in {dist}: {wheels}")
    wheel = wheels[0]
    check(wheel.name.startswith(f"mjarm-{version}-"), f"{wheel.name} has version {version}")

    # what the wheel holds: the package and its metadata, nothing of tests or examples
    with zipfile.ZipFile(wheel) as archive:
        names = set(archive.namelist())
        info = f"mjarm-{version}.dist-info"
        metadata = archive.read(f"{info}/METADATA").decode()
        entry_points = archive.read(f"{info}/entry_points.txt").decode()
    strays = sorted(n for n in names if not n.startswith(("mjarm/", info + "/")))
    check(not strays, f"the wheel holds only mjarm/ and {info}/, also: {strays[:5]}")
    for member in ["mjarm/__init__.py", "mjarm/__main__.py", "mjarm/_paths.py",
                   "mjarm/_mujoco_version.py", "mjarm/py.typed",
                   "mjarm/_mjarm.pyi", "mjarm/gym.py", "mjarm/bin/mjarm", "mjarm/models/panda.xml"]:
        check(member in names, f"the wheel holds {member}")
    check(any(re.fullmatch(r"mjarm/_mjarm\.cpython-.*\.so", n) for n in names),
          "the wheel holds the extension")
    check(any(n.startswith("mjarm/models/grippers/") for n in names),
          "the wheel holds the bundled grippers")
    check(f"Requires-Dist: {mujoco_pin}" in metadata, f"the wheel requires {mujoco_pin}")
    check("Requires-Dist: numpy" in metadata, "the wheel requires numpy")
    check(re.search(r"^mjarm = mjarm\.__main__:main$", entry_points, re.M) is not None,
          "console script mjarm = mjarm.__main__:main")

    # a fresh environment, the wheel and its dependencies from the index; installed by this
    # interpreter's pip into it (--python): bootstrapping a pip of its own (ensurepip) would cost
    # more than the install, and nothing here uses it
    python = make_venv(work / "venv", with_pip=False)
    run([sys.executable, *PIP, "--python", python, "install", "-q", "--no-compile", wheel])
    site = Path(run([python, "-c", "import sysconfig; print(sysconfig.get_paths()['platlib'])"])
                .strip())
    package, libmujoco = site / "mjarm", site / "mujoco" / f"libmujoco.so.{mujoco_version}"

    # the binaries: run paths relative to themselves, into the environment's mujoco
    extension = next(package.glob("_mjarm.cpython-*.so"))
    for binary, runpath in [(package / "bin" / "mjarm", "$ORIGIN/../../mujoco"),
                            (extension, "$ORIGIN/../mujoco")]:
        dynamic = run(["readelf", "-d", binary])
        # a sanitized build's binaries find the sanitizer runtime first, in its own folder
        expected = ":".join([str(Path(lib).parent) for lib in preload[:1]] + [runpath])
        check(f"[{expected}]" in dynamic and dynamic.count("RUNPATH") == 1,
              f"{binary.name}'s run path is {expected} only")
        check(f"[libmujoco.so.{mujoco_version}]" in dynamic, f"{binary.name} needs libmujoco")
        linked = run(["ldd", binary])
        check("not found" not in linked, f"ldd {binary.name} finds every library:\n{linked}")
        resolved = [Path(line.split("=>")[1].split("(")[0].strip()).resolve()
                    for line in linked.splitlines() if "libmujoco" in line and "=>" in line]
        check(resolved == [libmujoco.resolve()], f"ldd {binary.name} resolves {libmujoco}:\n{linked}")
        check(str(source / "models").encode() not in binary.read_bytes(),
              f"{binary.name} does not know the source tree's models")

    # used from elsewhere, with nothing pointing into the source or build tree
    env = {k: v for k, v in os.environ.items()
           if k != "PYTHONPATH" and not k.startswith("MJARM_")}
    if preload:
        # as make test's Python suite: the runtime first; CPython keeps memory until exit
        env.update(LD_PRELOAD=":".join(preload), ASAN_OPTIONS="detect_leaks=0")
    outside = work / "elsewhere"
    outside.mkdir(exist_ok=True)

    def use(*command):
        return run(command, cwd=outside, env=env)

    use(python, source / "tests" / "wheel" / "installed_check.py", version, mujoco_version)
    printed = use(python, "-m", "mjarm", "--version").strip()
    check(printed == f"mjarm {version} (MuJoCo {mujoco_version})", f"--version: {printed!r}")
    console = python.parent / "mjarm"
    fk = json.loads(use(console, "fk", "panda", "--json"))
    check(fk.get("model") == "panda", f"mjarm fk panda --json: {fk}")
    listing = json.loads(use(console, "info", "--list", "--json"))
    check(listing.get("models_dir") == str(package / "models"),
          f"mjarm info finds the package's models: {listing.get('models_dir')}")
    check("panda" in listing.get("models", []), f"mjarm info lists panda: {listing}")

    # the replay page: in the wheel where node and npm were found when it was built
    # (pyproject.toml's MJARM_WEB=AUTO; make test's machine has them), written by the installed
    # CLI and from Python
    with_page = shutil.which("node") is not None and shutil.which("npm") is not None
    recording, page, again = outside / "pick", outside / "pick.html", outside / "again.html"
    if with_page:
        use(console, "run", "shelf-pick", "--robot", "planar2", "--settle-time", "0.3",
            "--record", recording, "--html")
        check(page.exists() and page.read_text().startswith("<!doctype html>"),
              f"mjarm run … --html wrote {page}")
    # one interpreter for both calls (each start loads NumPy, mujoco and the extension)
    printed = use(python, "-c", "import mjarm, sys; print(mjarm.replay_html_available()); "
                  "mjarm.replay_html_available() and "
                  "print(mjarm.replay_html(sys.argv[1], sys.argv[2])['bytes'])",
                  recording, again).split()
    available = printed[0] if printed else ""
    check(available == str(with_page), f"mjarm.replay_html_available() is {with_page}: {available}")
    if with_page:
        written = printed[1] if len(printed) > 1 else ""
        check(again.exists() and written == str(again.stat().st_size),
              f"mjarm.replay_html wrote {again} ({written} bytes)")

    if failures:
        sys.exit(f"{len(failures)} checks failed")
    print(f"wheel {wheel.name}: every check passed")


if __name__ == "__main__":
    main()
