#!/usr/bin/env python3
"""Checks every link of a built HTML site (scripts/book.sh): each relative href and src
(a, img, link, script) must name a file of the site, and each #fragment an id (or an
<a name>) of its page. Links to other sites (http:, https:, mailto:) are counted, not
followed. Prints each broken link with its page and exits 1 if there is one.

usage: check-links.py SITE_DIR
"""
import os
import sys
from html.parser import HTMLParser
from urllib.parse import unquote, urlsplit


class Page(HTMLParser):
    """The ids and the links of one page."""

    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.ids = set()
        self.links = []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if a.get("id"):
            self.ids.add(a["id"])
        if tag == "a" and a.get("name"):
            self.ids.add(a["name"])
        for key in ("href", "src"):
            if a.get(key) and tag in ("a", "img", "link", "script"):
                self.links.append(a[key])


def parse(path):
    page = Page()
    with open(path, encoding="utf-8") as f:
        page.feed(f.read())
    return page


def main(site):
    pages = {}
    for root, _, files in os.walk(site):
        for name in files:
            if name.endswith(".html"):
                path = os.path.normpath(os.path.join(root, name))
                pages[path] = parse(path)
    broken, external, checked = [], 0, 0
    for path, page in sorted(pages.items()):
        for link in page.links:
            if not link.strip():
                broken.append((path, repr(link), "an empty link"))
                continue
            if link.startswith("/") and not link.startswith("//"):
                broken.append((path, link, "a path from the server's root: write it relative"))
                continue
            parts = urlsplit(link)
            if parts.scheme or link.startswith("//"):
                external += 1
                continue
            checked += 1
            target = path
            if parts.path:
                target = os.path.normpath(
                    os.path.join(os.path.dirname(path), unquote(parts.path)))
                if os.path.isdir(target):
                    target = os.path.join(target, "index.html")
                if not os.path.isfile(target):
                    broken.append((path, link, "no such file"))
                    continue
            if parts.fragment and target.endswith(".html"):
                ids = pages[target].ids if target in pages else parse(target).ids
                if unquote(parts.fragment) not in ids:
                    broken.append((path, link, "no such anchor"))
    for path, link, why in broken:
        print("%s: %s: %s" % (os.path.relpath(path, site), link, why))
    print("%d pages, %d links checked, %d to other sites not followed, %d broken"
          % (len(pages), checked, external, len(broken)))
    return 1 if broken else 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
