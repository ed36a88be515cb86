"""The input side: configuration files (TOML, survey CSV) read into the objects of the
model and the physics (:mod:`torsio.config.reading`, :mod:`torsio.config.configuration`)."""
