"""Teaching material shared by the worked solutions and the exercises: the textbook mechanisms
(presets)."""
