"""The wheel/rail contact of a passage: the protocol the drivers use (:mod:`.protocol`),
the profile contact (:mod:`.profile`, the default), the wheelsets' combined contact object
of a full vehicle (:mod:`.vehicle_contacts`) and the height-table baseline
(:mod:`.height_table`, imported by the dispatch only)."""
