"""What every job's HTML report is made of, kept once below the jobs that write reports
(``sweep``'s and ``optimize``'s): table cells (``cells``), the page's style, tables and figure
embedding (``page``), the passive verdict of one design with the strip of its nominal drops
(``verdict_section``), and the figures' shared pieces (``figures``). A job's report imports
these; it never imports another job's report.
"""
