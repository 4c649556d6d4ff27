"""The ``rotorsim`` command line: thin subcommands over model files, analyses, result files
and figures (``main``, ``parser``, ``adhoc``, ``outputs``, ``summaries``, ``completeness``).

The outermost layer: it may import everything; only ``python -m rotorsim``
(``rotorsim.__main__``) imports it.
"""
