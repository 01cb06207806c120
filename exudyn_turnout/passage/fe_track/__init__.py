"""fe_track"""
