"""The design flags and their parser, shared by the ``onefold`` command and the
explorer: the flag table (:mod:`.design_flags`), the parser that reads them
(:mod:`.parser`), flag values in template data (:mod:`.overrides`) and the
designs they make from templates (:mod:`.jobs`). No numpy: the command's
``--help`` needs none.
"""
