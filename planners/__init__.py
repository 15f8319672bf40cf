"""The OMPL side: state and control spaces, a level as validity checker and propagator, goals,
projections and planners by name. ``plan`` runs one planning query and returns plain data."""
