#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Checks every internal link and image of a built HTML site: each href/src that is not external must name an
existing file, and each #fragment an id (or name) in the target page.  Usage: check_links.py HTML_DIR
External links (http:, https:, mailto:) are not fetched: the build runs without network."""
import html.parser
import os
import sys
import urllib.parse


class Page(html.parser.HTMLParser):
    """The ids of a page and its references (tag, attribute, value)."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.ids, self.refs = set(), []

    def handle_starttag(self, tag, attrs):
        for k, v in attrs:
            if k in ("id", "name") and v:
                self.ids.add(v)
            if v and ((k == "href" and tag in ("a", "link")) or (k == "src" and tag in ("img", "script", "iframe"))):
                self.refs.append((tag, k, v))


def parse(path, cache):
    if path not in cache:
        p = Page()
        with open(path, encoding="utf-8", errors="replace") as f:
            p.feed(f.read())
        cache[path] = p
    return cache[path]


def check(root):
    """Returns the list of broken references, 'page: tag attr=value (why)'."""
    root = os.path.abspath(root)
    cache, problems = {}, []
    for dirpath, _, files in os.walk(root):
        for name in files:
            if not name.endswith(".html"):
                continue
            page = os.path.join(dirpath, name)
            for tag, attr, value in parse(page, cache).refs:
                u = urllib.parse.urlsplit(value)
                if u.scheme or u.netloc or value.startswith("//"):
                    continue  # external (http, https, mailto, data): not fetched
                target = page if not u.path else os.path.normpath(
                    os.path.join(dirpath, urllib.parse.unquote(u.path)))
                if os.path.isdir(target):
                    target = os.path.join(target, "index.html")
                where = f"{os.path.relpath(page, root)}: <{tag} {attr}={value}>"
                if not target.startswith(root):
                    problems.append(f"{where} (outside the site)")
                elif not os.path.isfile(target):
                    problems.append(f"{where} (no such file)")
                elif u.fragment and target.endswith(".html") and tag == "a" and \
                        urllib.parse.unquote(u.fragment) not in parse(target, cache).ids:
                    problems.append(f"{where} (no anchor #{u.fragment})")
    return problems


if __name__ == "__main__":
    found = check(sys.argv[1])
    print("\n".join(found) or "all internal links and images resolve")
    sys.exit(1 if found else 0)
