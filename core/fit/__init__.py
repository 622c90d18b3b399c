"""Fitting a card's model from the robot's own logs (issue 44): read a WPILog or an AdvantageScope
CSV (logs), find a SysId routine's signals (signals), fit kS, kV, kA, kG as SysId does (sysid_fit),
turn the gains into the card's entries (entries) and replay the logged voltage through the card's
model (replay)."""
