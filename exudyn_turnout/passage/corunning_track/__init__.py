"""corunning_track"""
