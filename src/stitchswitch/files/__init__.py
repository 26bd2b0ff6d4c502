"""Files the package reads and writes, each way of doing it once.

* ``atomic``: ``atomic_write_bytes`` / ``atomic_write_text``: a reader sees the old file or the
  whole new one, never a part.
* ``outputs``: ``check_output_file`` (an output path refused before any work, naming the
  user's path), ``check_distinct``, ``together`` (the files of one command replace their
  targets all or none).
* ``tempnames``: ``temp_path`` / ``remove_stale``: temporary entries named with the writer's
  pid, and those of killed writers removed by the next write.
* ``outdir``: output folders written as a whole (``check_outdir`` before computing, ``building``
  and ``write_outdir`` after), a non-empty target refused unless forced.
* ``textio``: ``read_text``, ``csv_records``, ``csv_number``: user text files with one clear error
  per problem, naming the file and the line.
* ``revolution``: ``surface_of_revolution`` of a 1D profile and ``write_mesh`` (VTU/PLY/OBJ
  through meshio).
* ``html_page``: ``page`` of ``Section`` / ``Paragraph`` / ``ItemList`` / ``Table`` / ``Figure``
  blocks, a self-contained HTML page (one stylesheet, text escaped, PNG/SVG as data URIs).
* ``jsonsafe``: ``json_safe``, numpy scalars to Python ones and nan/inf to null for strict JSON.
* ``json_checks``: ``loads`` / ``load_file`` and the typed checks (``obj``, ``array``, ``items``,
  ``text``, ``number``, ``integer``, ``choice``, ``unique``) of the JSON files the package reads
  (design, machine catalogue, material), each error naming the file and the JSON path.
* ``shown``: ``show`` / ``show_all`` / ``clip``, input values shortened for error messages (every
  message that repeats a value uses them).
* ``extensions``: ``check_extension``, an output path's extension checked before any work.
* ``figures``: ``plot_bytes``, a matplotlib figure as PNG / SVG / PDF bytes without date or
  version stamps (byte-reproducible), the figure closed after.

Nothing here knows about the model: every other sub-package may import it.
"""
