"""What is designed: the 12 design parameters, the feeder built from them, the part, scenes.

Pure data and geometry; nothing here knows of OMPL.
"""
