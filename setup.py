# The Python package mrs_vpr (python/mrs_vpr), installed by catkin_python_setup() beside the generated
# mrs_vpr.msg and mrs_vpr.srv; the extension module mrs_vpr._bindings is built by CMakeLists.txt.
from catkin_pkg.python_setup import generate_distutils_setup
from setuptools import setup

setup(**generate_distutils_setup(packages=["mrs_vpr"], package_dir={"": "python"}))
