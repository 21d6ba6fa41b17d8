"""A site of several sheets: the site file's model (:mod:`.spec`), where each
sheet stands on the site (:mod:`.placement`) and the clearance between them
(:mod:`.clearance`). Numpy and the standard library only; the files are
written by ``onefold_cad.export`` and the command is ``onefold site``."""
