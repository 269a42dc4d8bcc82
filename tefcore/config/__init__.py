"""Configuration: what a rotor with a trailing-edge flap is, typed, validated, with units.

The ground floor of the solver: it imports no physics.  A configuration is
data (declared fields with units, ranges and sources) and the checks that
need only the fields; checks that need the assembled blade run where the
blade is built (:mod:`tefcore.structure.blade`).

Its modules (import each by name; the package itself exports nothing)::

    settings    declarative settings: typed, unit-aware fields declared once as data
    sections    the configuration and its sections (rotor, blade, flap, actuator, flight, model)
    hub         the sections of the bearingless hub's multiple load paths
    io          TOML reading and writing, packaged configurations, the settings table
    text_input  values given as text (command line, TOML) and the units rule
"""

__all__: list[str] = []
