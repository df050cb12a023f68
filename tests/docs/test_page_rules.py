"""page_rules.py on small synthetic pages: each rule fails when it should and passes when it should
(run by `test_docs.py page_rules`, ctest docs.page_rules)."""

import unittest

import page_rules


def lines(n, word="text"):
    return "".join(f"{word} {k}\n" for k in range(n))


def words(n, per_line=20):
    return "".join(" ".join("word" for _ in range(min(per_line, n - k))) + "\n" for k in range(0, n, per_line))


def newcomer_pages(readme=10, each=10):
    pages = {path: lines(each) for path in page_rules.NEWCOMER_PAGES}
    pages["README.md"] = lines(readme)
    return pages


# The decks the cost rule knows by name (page_rules.DECK_NAMES), as a tree holds them.
DECKS = {"inputs/in.chute": "# the chute\nvariable L index 45\n",
         "inputs/in.default_scene": "# the chute on a small cell\ninclude inputs/in.chute\n"}

CHUTE_COST = ("## Default scene\n\n"
              "The deck takes 22 CPU s on one core. <!-- cost: in.default_scene -->\n")


def problems_of(files):
    return page_rules.cost_problems({**DECKS, **files})


class Lengths(unittest.TestCase):
    def test_a_page_at_its_limit_passes_and_one_line_more_fails(self):
        pages = newcomer_pages()
        pages["doc/study.md"] = lines(300)
        self.assertEqual(page_rules.length_problems(pages), [])
        pages["doc/study.md"] = lines(301)
        self.assertEqual(len(page_rules.length_problems(pages)), 1)
        self.assertIn("doc/study.md: 301 lines", page_rules.length_problems(pages)[0])

    def test_rst_pages_and_pages_in_doc_folders_count(self):
        pages = newcomer_pages()
        pages["doc/fix.rst"] = lines(301)
        pages["doc/accuracy/table.md"] = lines(400)
        found = page_rules.length_problems(pages)
        self.assertEqual(len(found), 2)
        self.assertTrue(found[0].startswith("doc/accuracy/table.md") and found[1].startswith("doc/fix.rst"))

    def test_the_readme_has_its_own_limit(self):
        self.assertEqual(page_rules.length_problems(newcomer_pages(readme=100)), [])
        found = page_rules.length_problems(newcomer_pages(readme=101))
        self.assertEqual(len(found), 1)
        self.assertIn("README.md: 101 lines, more than 100", found[0])

    def test_the_results_page_has_its_own_limit_and_other_results_pages_none(self):
        pages = newcomer_pages()
        pages["results/README.md"] = lines(250)
        pages["results/runs/README.md"] = lines(900)
        self.assertEqual(page_rules.length_problems(pages), [])
        pages["results/README.md"] = lines(251)
        found = page_rules.length_problems(pages)
        self.assertEqual(len(found), 1)
        self.assertIn("results/README.md: 251 lines, more than 250", found[0])

    def test_dated_notes_have_no_limit_and_other_names_are_refused(self):
        pages = newcomer_pages()
        pages["doc/notes/2026-11-25-accuracy.md"] = lines(900)
        self.assertEqual(page_rules.length_problems(pages), [])
        pages["doc/notes/accuracy.md"] = lines(3)
        found = page_rules.length_problems(pages)
        self.assertEqual(len(found), 1)
        self.assertIn("doc/notes/accuracy.md: a note is named", found[0])

    def test_the_newcomer_pages_together(self):
        # Seven pages: 600 + 6 x 900 = 6000 words passes; 600 + 6 x 901 = 6006 fails though every
        # page is within its lines.
        pages = {path: words(900) for path in page_rules.NEWCOMER_PAGES}
        pages["README.md"] = words(600)
        self.assertEqual(page_rules.length_problems(pages), [])
        pages = {path: words(901) for path in page_rules.NEWCOMER_PAGES}
        pages["README.md"] = words(600)
        found = page_rules.length_problems(pages)
        self.assertEqual(len(found), 1)
        self.assertIn("6006 words together, more than 6000", found[0])
        self.assertIn("doc/plane_shear.md 901", found[0])

    def test_a_missing_newcomer_page_is_named(self):
        pages = newcomer_pages()
        del pages["doc/chute.md"]
        found = page_rules.length_problems(pages)
        self.assertEqual(found, ["a newcomer page is missing: doc/chute.md"])


class History(unittest.TestCase):
    def test_sections_and_phrases_of_a_study_log_are_found_on_reference_pages_only(self):
        log = ("# Accuracy\n\nThe defaults.\n\n## Open\n\n- more runs\n\nEarlier\n-------\n\n"
               "Measured at commit fbf61fa: 22 s. A prototype, not kept.\n```sh\n## Open\n```\n")
        found = page_rules.history_problems({"doc/accuracy.md": log, "doc/notes/2026-11-25-accuracy.md": log})
        self.assertEqual([p.split(": ")[0] for p in found],
                         ["doc/accuracy.md:5", "doc/accuracy.md:9", "doc/accuracy.md:12", "doc/accuracy.md:12"], found)
        self.assertIn("a section 'Open'", found[0])
        self.assertIn("'Measured at commit'", found[2])
        self.assertIn("'not kept'", found[3])

    def test_a_reference_page_passes(self):
        page = "# Accuracy\n\n## What decides\n\nThe deck keeps 1e-4 s; the open cell is periodic.\n"
        self.assertEqual(page_rules.history_problems({"doc/accuracy.md": page, "README.md": page}), [])


class Costs(unittest.TestCase):
    def test_one_marked_statement_and_links_pass(self):
        found = problems_of({"doc/chute.md": CHUTE_COST,
                             "README.md": "The default scene runs for 1.5 s (its cost: doc/chute.md).\n"})
        self.assertEqual(found, [])

    def test_the_three_ways_of_today_are_each_found(self):
        found = problems_of({
            "doc/chute.md": CHUTE_COST,
            "README.md": "## The default scene\n\n`scripts/run_default_scene.sh` rains 400 disks and\n"
                         "tilts gravity for 1.5 s (about half a CPU minute).\n",
            "inputs/in.default_scene": "# Default scene: a small chute.\n# A few minutes on one core.\n"
                                       "variable L index 20\n"})
        self.assertEqual(len(found), 2, found)
        self.assertTrue(found[0].startswith("README.md:3: a CPU time of in.default_scene"), found[0])
        self.assertIn("doc/chute.md:3", found[0])
        self.assertIn("half a CPU minute", found[0])
        self.assertTrue(found[1].startswith("inputs/in.default_scene:1: a CPU time of in.default_scene"))

    def test_without_a_marker_every_cpu_time_of_the_deck_is_an_error(self):
        found = problems_of({"doc/chute.md": CHUTE_COST.replace("<!-- cost: in.default_scene -->", "")})
        self.assertEqual(len(found), 1)
        self.assertIn("none is marked `cost: in.default_scene`", found[0])

    def test_a_section_heading_names_the_deck(self):
        page = CHUTE_COST + "\n## The default scene again\n\nIt took 25 CPU s here.\n"
        found = problems_of({"doc/chute.md": page})
        self.assertEqual(len(found), 1)
        self.assertTrue(found[0].startswith("doc/chute.md:7:"), found[0])

    def test_every_cpu_time_phrase_counts(self):
        for phrase in ("22 CPU s", "half a CPU minute", "3 CPU-hours", "a few minutes on one core",
                       "about a day of one core", "40 core hours", "12 CPU seconds per physical second"):
            found = problems_of({"doc/chute.md": CHUTE_COST, "doc/x.md": f"The default scene costs {phrase}.\n"})
            self.assertEqual(len(found), 1, phrase)

    def test_costs_relative_to_the_marked_one_and_other_times_pass(self):
        found = problems_of({"doc/chute.md": CHUTE_COST,
                             "doc/x.md": "The default scene at dt 5e-5 s: 1.4x its cost, 2 minutes of wall time.\n"})
        self.assertEqual(found, [])

    def test_a_deck_named_by_a_longer_name_is_another_deck(self):
        found = problems_of({"doc/chute.md": CHUTE_COST,
                             "doc/reference.md": "`reference/in.chute_rigid` costs 9 CPU s per physical s.\n"})
        self.assertEqual(found, [])

    def test_two_markers_for_one_deck(self):
        found = problems_of({"doc/chute.md": CHUTE_COST, "README.md": CHUTE_COST})
        self.assertTrue(any("in.default_scene is marked 2 times: README.md:3, doc/chute.md:3" in p for p in found),
                        found)

    def test_a_marker_naming_no_deck_or_marking_no_cpu_time(self):
        found = problems_of({"doc/chute.md": CHUTE_COST,
                             "doc/a.md": "It takes 3 CPU s. <!-- cost: in.nothing -->\n",
                             "doc/b.md": "<!-- cost: in.chute -->\n\nThe chute deck runs long.\n"})
        self.assertEqual(len(found), 2, found)
        self.assertIn("doc/a.md:1: the cost marker names in.nothing", found[0])
        self.assertIn("doc/b.md:3: the cost marker of in.chute marks a statement that gives no CPU time", found[1])

    def test_a_table_is_one_statement_its_marker_on_the_line_above(self):
        table = "<!-- cost: in.chute -->\n| setting | CPU s per physical s |\n|---|---|\n| defaults | 74 |\n"
        found = problems_of({"doc/chute.md": CHUTE_COST, "doc/accuracy.md": "# On the 45 d scene\n\n" + table,
                             "doc/bench.md": "The 45 d scene costs 91 CPU s per physical second.\n"})
        self.assertEqual(len(found), 1, found)
        self.assertTrue(found[0].startswith("doc/bench.md:1: a CPU time of in.chute outside its cost "
                                            "statement (doc/accuracy.md:3)"), found[0])

    def test_list_items_are_statements_of_their_own(self):
        page = CHUTE_COST + "\n## Runs\n\n- The default scene writes a report.\n- A run of in.chute: 15 CPU minutes.\n"
        found = problems_of({"doc/chute.md": page})
        self.assertEqual(len(found), 1, found)
        self.assertTrue(found[0].startswith("doc/chute.md:8: a CPU time of in.chute"), found[0])

    def test_fenced_blocks_and_rest_pages(self):
        rst = ("Default scene\n=============\n\n.. cost: in.default_scene\n\nIt takes 22 CPU s.\n\n"
               "Other\n-----\n\nThe 45 d scene takes 74 CPU s per physical second.\n")
        found = problems_of({"doc/fix.rst": rst,
                             "doc/chute.md": "```sh long\nlmp_cd -in inputs/in.chute   # 20 CPU minutes\n```\n"})
        self.assertEqual(len(found), 2, found)
        self.assertIn("doc/chute.md:1: a CPU time of in.chute", found[0])
        self.assertIn("doc/fix.rst:11: a CPU time of in.chute", found[1])

    def test_a_marker_alone_marks_the_next_statement(self):
        page = "## Default scene\n\n<!-- cost: in.default_scene -->\n\nIt takes 22 CPU s.\n\nAnd 30 CPU s.\n"
        found = problems_of({"doc/chute.md": page})
        self.assertEqual(len(found), 1, found)
        self.assertTrue(found[0].startswith("doc/chute.md:7: a CPU time of in.default_scene outside its cost "
                                            "statement (doc/chute.md:5)"), found[0])
        found = problems_of({"doc/chute.md": "It takes 22 CPU s.\n\n<!-- cost: in.default_scene -->\n"})
        self.assertIn("doc/chute.md:3: the cost marker of in.default_scene marks a statement that gives no", found[0])

    def test_notes_are_not_read(self):
        found = problems_of({"doc/chute.md": CHUTE_COST,
                             "doc/notes/2026-11-20-default-scene.md": "The default scene took 30 CPU s then.\n"})
        self.assertEqual(found, [])


if __name__ == "__main__":
    unittest.main()


class Links(unittest.TestCase):
    TREE = {"results/README.md", "results/runs", "results/runs/README.md", "results/series/a/figures/f.png",
            "doc/chute.md"}

    def problems(self, pages):
        return page_rules.link_problems(pages, lambda path: path in self.TREE)

    def test_links_resolved_from_the_page_folder_pass(self):
        page = ("See [the runs](runs/README.md), [folder](runs), ![f](series/a/figures/f.png), "
                "[a section](runs/README.md#flow), [the web](https://example.org/x), [here](#top), "
                "[the chute](../doc/chute.md).\n")
        self.assertEqual(self.problems({"results/README.md": page}), [])
        self.assertEqual(self.problems({"results/runs/README.md": "[up](../README.md)\n"}), [])

    def test_a_link_naming_nothing_is_found_with_its_line(self):
        page = "title\n\n![f](series/a/figures/g.png) and [runs](../runs/README.md)\n"
        found = self.problems({"results/README.md": page})
        self.assertEqual(len(found), 2)
        self.assertIn("results/README.md:3: the link series/a/figures/g.png names nothing", found[0])
        self.assertIn("(runs/README.md)", found[1])

    def test_only_markdown_pages_are_read(self):
        self.assertEqual(self.problems({"doc/fix.rst": "`x <missing.md>`_ [y](missing.md)\n"}), [])
