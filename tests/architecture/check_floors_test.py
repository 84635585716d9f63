"""scripts/check_floors.py on made-up trees: a tree that keeps its floors passes, and each way of
breaking them fails naming the file, the line and the arrow. Standard library only (unittest), run
by CTest as `architecture_floors_selftest`."""

import os
import subprocess
import sys
import tempfile
import unittest

CHECKER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts",
                       "check_floors.py")

# rooms a (floor 0), b (floor 1, reads a), c (floor 1, reads a: listed, never used), the CLI on top
DOCS = """\
# Architecture

## Rooms
```
floor  2   app/
floor  1   b/ c/
floor  0   a/   + the top level
```

| floor | room | holds | reads from |
|---|---|---|---|
| 0 | `a/` | the ground (with a note, (nested)) | — (Eigen) |
| 1 | `b/` | reads a | a (the only arrow) |
| 1 | `c/` | reads nothing yet | a |
| 2 | `app/` | the CLI | every room below |

## Build
"""


def includes(*names):
    """The text of a file that includes `names` in order ("<x>" for angle brackets)."""
    quoted = (name if name.startswith("<") else f'"{name}"' for name in names)
    return "".join(f"#include {name}\n" for name in quoted)


FILES = {
    "include/mjarm/error.hpp": "#pragma once\n",
    "include/mjarm/a/a.hpp": "#pragma once\n" + includes("mjarm/error.hpp"),
    "include/mjarm/a/detail/a_impl.hpp": "#pragma once\n",
    "include/mjarm/b/b.hpp": "#pragma once\n" + includes("mjarm/a/a.hpp", "<vector>"),
    "include/mjarm/c/c.hpp": "#pragma once\n",
    "src/a/a.cpp": includes("mjarm/a/a.hpp", "a_private.hpp", "mjarm/a/detail/a_impl.hpp"),
    "src/a/a_private.hpp": "#pragma once\n",
    "src/b/b.cpp": includes("mjarm/b/b.hpp", "shared.hpp", "<Eigen/Core>"),
    "src/c/c.cpp": includes("mjarm/c/c.hpp"),
    "src/shared.hpp": "#pragma once\n" + includes("mjarm/error.hpp"),
    "app/main.cpp": includes("mjarm/b/b.hpp", "mjarm/a/a.hpp", "commands.hpp"),
    "app/commands.hpp": "#pragma once\n",
}


class CheckFloors(unittest.TestCase):
    def run_checker(self, changes=None, docs=DOCS):
        """Runs the checker on the made-up tree with `changes` (path -> text, None removes)."""
        files = dict(FILES)
        files.update(changes or {})
        with tempfile.TemporaryDirectory() as root:
            for path, text in list(files.items()) + [("docs/architecture.md", docs)]:
                if text is None:
                    continue
                full = os.path.join(root, path)
                os.makedirs(os.path.dirname(full), exist_ok=True)
                with open(full, "w", encoding="utf-8") as f:
                    f.write(text)
            done = subprocess.run([sys.executable, CHECKER, "--root", root, "--graph"],
                                  capture_output=True, text=True, check=False)
        return done.returncode, done.stdout + done.stderr

    def assert_fails(self, expected, changes=None, docs=DOCS):
        code, output = self.run_checker(changes, docs)
        self.assertEqual(code, 1, output)
        for text in expected:
            self.assertIn(text, output)

    def test_a_tree_that_keeps_its_floors_passes_and_lists_the_unused_arrow(self):
        code, output = self.run_checker()
        self.assertEqual(code, 0, output)
        self.assertIn("architecture floors: ok (4 rooms, 3 arrows", output)
        self.assertIn("b (floor 1) -> a", output)
        self.assertIn("app (floor 2) -> a b", output)
        self.assertIn("info: arrows docs/architecture.md allows that no include uses: c -> a",
                      output)

    def test_an_include_of_a_higher_floor_fails(self):
        self.assert_fails(['src/a/a.cpp:2: #include "mjarm/b/b.hpp": arrow a -> b is not in the '
                           "table: b is on floor 1, not below a's floor 0"],
                          {"src/a/a.cpp": includes("mjarm/a/a.hpp", "mjarm/b/b.hpp")})

    def test_an_include_of_the_same_floor_fails(self):
        self.assert_fails(["include/mjarm/c/c.hpp:2: #include <mjarm/b/b.hpp>: arrow c -> b is "
                           "not in the table: b is on floor 1, not below c's floor 1"],
                          {"include/mjarm/c/c.hpp": "#pragma once\n" + includes("<mjarm/b/b.hpp>")})

    def test_an_arrow_below_that_the_row_does_not_list_fails(self):
        docs = DOCS.replace("| reads a | a (the only arrow) |", "| reads a | — |")
        self.assert_fails(['include/mjarm/b/b.hpp:2: #include "mjarm/a/a.hpp": arrow b -> a is '
                           "not in the table: b reads only no room"], docs=docs)

    def test_a_room_missing_from_the_table_fails(self):
        self.assert_fails(["room d (include/mjarm/d or src/d) is not in docs/architecture.md's "
                           "rooms table"], {"src/d/d.cpp": includes("mjarm/a/a.hpp")})

    def test_a_room_of_the_table_without_a_folder_fails(self):
        self.assert_fails(["docs/architecture.md:14: room c has no folder"],
                          {"include/mjarm/c/c.hpp": None, "src/c/c.cpp": None})

    def test_a_private_header_of_another_room_fails(self):
        self.assert_fails(['src/b/b.cpp:2: #include "a/a_private.hpp": arrow b -> a: '
                           "src/a/a_private.hpp is a private header of a"],
                          {"src/b/b.cpp": includes("mjarm/b/b.hpp", "a/a_private.hpp")})

    def test_a_detail_header_of_another_room_fails(self):
        self.assert_fails(['src/b/b.cpp:2: #include "mjarm/a/detail/a_impl.hpp": arrow b -> a: '
                           "include/mjarm/a/detail/a_impl.hpp is a private header of a"],
                          {"src/b/b.cpp": includes("mjarm/b/b.hpp", "mjarm/a/detail/a_impl.hpp")})

    def test_a_public_header_that_includes_a_private_one_fails(self):
        self.assert_fails(['include/mjarm/a/a.hpp:2: #include "a/a_private.hpp": arrow a -> a: '
                           "a public header includes src/a/a_private.hpp, which is not installed"],
                          {"include/mjarm/a/a.hpp": "#pragma once\n" + includes("a/a_private.hpp")})

    def test_the_cli_reading_a_private_header_fails(self):
        self.assert_fails(['app/main.cpp:2: #include "mjarm/a/detail/a_impl.hpp": arrow app -> a: '
                           "include/mjarm/a/detail/a_impl.hpp is private to the library"],
                          {"app/main.cpp": includes("mjarm/b/b.hpp", "mjarm/a/detail/a_impl.hpp")})

    def test_the_top_level_reading_a_room_fails(self):
        self.assert_fails(['src/shared.hpp:2: #include "mjarm/a/a.hpp": arrow (top level) -> a: '
                           "the top level is floor 0 and reads no room"],
                          {"src/shared.hpp": "#pragma once\n" + includes("mjarm/a/a.hpp")})

    def test_an_include_of_a_missing_mjarm_header_fails(self):
        self.assert_fails(["src/c/c.cpp:2: includes mjarm/c/gone.hpp, which does not exist"],
                          {"src/c/c.cpp": includes("mjarm/c/c.hpp", "mjarm/c/gone.hpp")})

    def test_a_table_arrow_that_goes_up_fails(self):
        docs = DOCS.replace("| 0 | `a/` | the ground (with a note, (nested)) | — (Eigen) |",
                            "| 0 | `a/` | the ground | b |")
        self.assert_fails(["docs/architecture.md:12: arrow a -> b goes from floor 0 to floor 1: "
                           "a room reads only rooms on lower floors"], docs=docs)

    def test_a_table_arrow_to_an_unknown_room_fails(self):
        docs = DOCS.replace("| reads nothing yet | a |", "| reads nothing yet | a, x |")
        self.assert_fails(["docs/architecture.md:14: room c reads from 'x', which is not a room "
                           "of the table"], docs=docs)

    def test_a_drawing_that_disagrees_with_the_table_fails(self):
        docs = DOCS.replace("floor  1   b/ c/", "floor  1   b/")
        docs = docs.replace("floor  2   app/", "floor  2   app/ c/")
        self.assert_fails(["docs/architecture.md:5: the drawing puts c on floor 2, the table "
                           "(line 14) on floor 1"], docs=docs)

    def test_docs_without_the_table_fail(self):
        self.assert_fails(["no rooms table under '## Rooms'"],
                          docs=DOCS.replace("| floor | room | holds | reads from |",
                                            "| room | holds |"))


if __name__ == "__main__":
    unittest.main()
