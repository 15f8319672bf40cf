"""Which names may become SQL columns through OMPL's log reader.

OMPL's ``ompl_benchmark_statistics`` (``ompl._benchmark_statistics.readBenchmarkLog``) adds
each experiment property of a log as a column of its ``experiments`` table with
``"ALTER TABLE experiments ADD %s %s" % (name, type)`` and inserts rows naming the columns the
same way: unquoted. A property named ``index``, ``order`` or ``select`` (SQL keywords) is a
syntax error there; one named ``seed`` or ``name`` (columns OMPL's table already has) is not
added and is listed twice in the insert. So such names are refused before they reach a log:
a name is a plain identifier (ASCII letters, digits, '_', not starting with a digit), not one
of SQLite's keywords and not a column of OMPL's ``experiments`` table, whatever its case
(SQLite compares both without case). Light: imports nothing of OMPL.
"""

from __future__ import annotations

import re

PLAIN_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")

# SQLite's keywords (sqlite3_keyword_name, SQLite 3.45: 147 of them;
# tests/planners/test_sql_names.py checks the linked library's list against this one)
SQL_KEYWORDS = frozenset(
    """ABORT ACTION ADD AFTER ALL ALTER ALWAYS ANALYZE AND AS ASC ATTACH AUTOINCREMENT BEFORE
    BEGIN BETWEEN BY CASCADE CASE CAST CHECK COLLATE COLUMN COMMIT CONFLICT CONSTRAINT CREATE
    CROSS CURRENT CURRENT_DATE CURRENT_TIME CURRENT_TIMESTAMP DATABASE DEFAULT DEFERRABLE
    DEFERRED DELETE DESC DETACH DISTINCT DO DROP EACH ELSE END ESCAPE EXCEPT EXCLUDE EXCLUSIVE
    EXISTS EXPLAIN FAIL FILTER FIRST FOLLOWING FOR FOREIGN FROM FULL GENERATED GLOB GROUP GROUPS
    HAVING IF IGNORE IMMEDIATE IN INDEX INDEXED INITIALLY INNER INSERT INSTEAD INTERSECT INTO IS
    ISNULL JOIN KEY LAST LEFT LIKE LIMIT MATCH MATERIALIZED NATURAL NO NOT NOTHING NOTNULL NULL
    NULLS OF OFFSET ON OR ORDER OTHERS OUTER OVER PARTITION PLAN PRAGMA PRECEDING PRIMARY QUERY
    RAISE RANGE RECURSIVE REFERENCES REGEXP REINDEX RELEASE RENAME REPLACE RESTRICT RETURNING
    RIGHT ROLLBACK ROW ROWS SAVEPOINT SELECT SET TABLE TEMP TEMPORARY THEN TIES TO TRANSACTION
    TRIGGER UNBOUNDED UNION UNIQUE UPDATE USING VACUUM VALUES VIEW VIRTUAL WHEN WHERE WINDOW
    WITH WITHOUT ROWID OID _ROWID_""".split()
)  # (ROWID, OID, _ROWID_: not keywords, but SQLite's names for a row's key)

# the columns OMPL's reader makes its ``experiments`` table with
OMPL_EXPERIMENT_COLUMNS = frozenset(
    "id name totaltime timelimit memorylimit runcount version hostname cpuinfo date seed "
    "setup".split()
)

RULE = (
    "a plain identifier (ASCII letters, digits and '_', not starting with a digit) that is "
    "not an SQL keyword (index, order, select, ...) and not a column of OMPL's experiments "
    f"table ({', '.join(sorted(OMPL_EXPERIMENT_COLUMNS))}), in any case"
)


def column_name_problem(name: object) -> str | None:
    """Why ``name`` cannot be an experiment property in OMPL's log (a column its reader adds
    unquoted), or None."""
    if not isinstance(name, str) or not PLAIN_IDENTIFIER.fullmatch(name):
        return "not a plain identifier"
    if name.upper() in SQL_KEYWORDS:
        return "an SQL keyword"
    if name.lower() in OMPL_EXPERIMENT_COLUMNS:
        return "a column OMPL's experiments table already has"
    return None
