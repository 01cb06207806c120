"""The passage's vehicles in Exudyn: the single wheelset with its sprung share
(:mod:`.wheelset`) and the full vehicle (:mod:`.builder`, its handles, static analysis and
the track-following frame's loads)."""
