"""Mode identity: which root is which, and the roles a root plays.

Labels from participation, matching between points (MAC and eigenvalue
distance), tracking along a parameter, continuation in the coupling and the
roles (the TEF mode, the flutter root).

Its modules (import each by name; the package itself exports nothing)::

    labels        a root's label from the coordinate it carries (participation)
    matching      matching modes between two points: MAC, eigenvalue distances, cost
    tracking      tracks along a parameter: one curve is one physical mode
    continuation  identity by continuation in the blade-flap coupling (the names)
    march         (private) the paths of continuation, one step of eps at a time
    final_names   (private) names at full coupling of the roots a path does not decide
    roles         the TEF mode, the flutter root, exceptional points along a sweep
"""

__all__: list[str] = []
