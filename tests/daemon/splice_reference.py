#!/usr/bin/env python3
"""Replaces the generated table in docs/configuration.md: splice_reference.py DOC TABLE."""
import sys

doc_path, table_path = sys.argv[1], sys.argv[2]
doc = open(doc_path).read()
begin = doc.index("<!-- BEGIN GENERATED")
begin = doc.index("\n", begin) + 1
end = doc.index("<!-- END GENERATED")
open(doc_path, "w").write(doc[:begin] + open(table_path).read() + doc[end:])
