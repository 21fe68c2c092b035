"""The study engine: cases -> runs -> JSON-line records -> reports, for every study.

- :mod:`.catalog`: the study list (every module that declares ``STUDY``) as :class:`~.catalog.Study` objects;
- :mod:`.case`: a case (one solver run of one scene) as data with an identity;
- :mod:`.solvers`: the solvers a case can name (check, run, source hash);
- :mod:`.worker`: one case run in any process; :mod:`.scheduler`: a study's cases over
  an executor, each record stored as it finishes; :mod:`.store`: the record files;
- :mod:`.pipeline`: run the named studies, then rebuild every report from records;
- :mod:`.report`: the report context, tables, figures and the README;
- :mod:`.regression`: the tiny-mode golden values; :mod:`.diff`: two record directories
  compared case by case.

A study (``studies/<module>.py``) only expands its grid into cases and renders its
report from records; nothing here knows a particular study.
"""
