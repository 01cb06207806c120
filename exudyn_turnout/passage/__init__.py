"""passage"""
