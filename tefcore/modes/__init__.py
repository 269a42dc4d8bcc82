"""Mode identity: which root is which, and the roles a root plays.

Labels from participation, matching between points (MAC and eigenvalue
distance), tracking along a parameter, continuation in the coupling and the
roles (the TEF mode, the flutter root).

Its modules (import each by name; the package itself exports nothing)::

    matching  matching modes between two points: MAC, eigenvalue distances, cost
    tracking  tracks along a parameter: one curve is one physical mode
"""

__all__: list[str] = []
