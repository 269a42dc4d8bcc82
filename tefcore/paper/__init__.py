"""The paper-replication layer: figures, claims, validation, notebooks, report.

The solver (``tefcore``) knows nothing of the paper; this subpackage defines
the paper's figures as analyses, loads what the paper states about them
(reference data and claims), checks the claims, and reproduces the figures
through notebooks into a report.
"""
