"""The engineering report of a model file: one self-contained HTML page.

- ``page``: the HTML building blocks (escaped text, tables, preformatted summaries,
  figures embedded as base64 PNG) and the document with its inline style; no network
  resource is referenced.
- ``build``: :func:`~rotorsim.report.build.write_report` runs the analyses a model file
  names, saves every result to ``report.h5`` and writes ``report.html`` beside it, each
  section naming the HDF5 group its numbers come from.
- ``bearing_life``: the rolling-bearing lives of the report (static load, transients,
  periodic branches over speed), each stored in ``report.h5``.

May import: every rotorsim layer (it is a front end, like ``cli``); matplotlib through
``plotting`` only, when a report is written.
"""
