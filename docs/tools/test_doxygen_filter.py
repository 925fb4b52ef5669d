#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The Doxygen filter's rules on a header written in the house style (the test docs_cpp_filter): what becomes
documentation and what stays a plain comment, with every line kept in place."""
import os
import sys
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import doxygen_filter  # noqa: E402

HEADER = '''// SPDX-License-Identifier: GPL-3.0-or-later
// The file's head comment: it describes the header, not what follows.
#pragma once

namespace btob::demo {

// ---- a section rule ----
// A request: this comment documents the struct below.
struct DemoRequest {
  double r = 0.15;          // restitution coefficient, in (0, 1)
  long iterations = 10, transient = 5;  // map iterations
  int blocks = 20;
  // Spread over two members:
  double lo = 0;
  double hi = 1;
  std::vector<double> w1_range{-2, 2};  // the strip's w1 range
  void validate() const;
  template <class V> void fields(V&& v) {
    // a comment in a function body stays plain
    v("blocks", blocks, "batch-means blocks, "
      "2..iterations");
  }
};

// A declaration with a long text.
struct Spec {
  static constexpr const char* summary = "one text written "
                                         "over two lines";
};

}  // namespace btob::demo'''


class FilterTest(unittest.TestCase):
    def setUp(self):
        self.lines = HEADER.split("\n")
        self.out = doxygen_filter.filter_lines(self.lines)

    def line(self, text):
        return self.out[next(i for i, x in enumerate(self.lines) if text in x)]

    def test_lines_kept_in_place(self):
        self.assertEqual(len(self.out), len(self.lines))

    def test_head_comment_and_rules_stay_plain(self):
        self.assertTrue(self.line("head comment").startswith("// The file"))
        self.assertTrue(self.line("section rule").startswith("// ----"))

    def test_comment_above_a_struct_documents_it(self):
        self.assertTrue(self.line("A request").startswith("/// A request"))

    def test_trailing_comment_documents_its_member(self):
        self.assertIn("///< restitution coefficient", self.line("double r = 0.15"))

    def test_several_declarators_each_get_the_comment(self):
        out = self.line("long iterations")
        self.assertIn("long iterations = 10; /**< map iterations */", out)
        self.assertIn("long transient = 5; /**< map iterations */", out)

    def test_member_without_comment_gets_its_flag_help(self):
        self.assertIn("/**< batch-means blocks, 2..iterations */", self.line("int blocks = 20;"))

    def test_comment_above_members_is_a_distributed_group(self):
        self.assertTrue(self.line("Spread over").lstrip().startswith("/** @{ */ /// Spread"))
        # The group runs to the last member of the block and closes on the next line, so that the last member's
        # own comment stays its documentation.
        self.assertTrue(self.line("w1_range").endswith("///< the strip's w1 range"))
        self.assertTrue(self.line("void validate").startswith("/** @} */   void validate"))

    def test_adjacent_string_literals_are_joined_in_place(self):
        self.assertIn('summary = "one text written over two lines";', self.line("one text written"))
        self.assertEqual(self.line("over two lines").strip(), "")

    def test_braced_initialiser_and_function_bodies(self):
        self.assertIn("///< the strip's w1 range", self.line("w1_range"))
        self.assertIn("///< restitution", self.line("double r = 0.15"))
        self.assertTrue(self.line("in a function body").lstrip().startswith("// a comment"))


if __name__ == "__main__":
    unittest.main()
