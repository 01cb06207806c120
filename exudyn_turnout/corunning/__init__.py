"""corunning"""
