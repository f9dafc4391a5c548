# Included by ctest after the discovered tests (TEST_INCLUDE_FILES): the tests labelled
# "large", which the sanitizer run (test preset fuzz, .ci/run's second step) leaves out, as it
# leaves out the CLI's tests (cli.example, cli.dicom: 139 s and 102 s, the phantom pipeline run
# many times; the preset does not build the CLI). Under ASan+UBSan these are 10-20x slower than
# in the release build; measured one at a time on the 2-core development VM, release in brackets:
#   SurfacesTest.Volume512x512x400WorksInSlabs  over 150 s (21 s)
#   Assembly.RandomVolumesAreWellFormed          60 s (3.8 s)
#   Smoothing.PhantomNeverCrosses                43 s (3.7 s)
#   Remesh.Phantom                               144 s (33 s)
#   RemeshBuildTest.BuildRemeshesThePhantomAfterSmoothing   87 s (12 s)
#   InterpolatedShapesTest.FinerGridsNeverIncreaseTheSphereError   46 s (10 s)
#   Remesh.SameResultForAnyThreadCount           24 s
#   IncidentalOverlapsTest.IndependentlyDrawnNeighboursShareOneSurface   74 s (10 s)
#   IncidentalOverlapsTest.ThreeNeighboursMeetingAtAJunction             52 s (5.4 s)
#   InterpolationVolumeTest.FewPlaneStructuresKeepTheirSlabVolume        33 s (5.7 s)
#   IncidentalOverlapsTest.SplitOnTheDeviceEqualsTheHostRoundTrip        21 s (2.6 s)
#   InterpolatedShapesTest.AccuracyAtThreeGridsAgainstOff   (8 s)
#   InterpolationVolumeTest.VolumesDoNotDependOnTheOtherStructures   (4.7 s)
# (ctest -j2 in the clean-clone CI run, 2026-11-30; the whole sanitizer run took 305 s with them.)
# The other 218 tests (every reader, writer and CPU unit test, the GPU passes on small shapes,
# the fuzz inputs) take 540 s one at a time, 274 s with ctest -j2 (the VM shared with other
# builds; 20-35 s the slowest, Smoothing.AbuttingHalvesNeverCross).
set_tests_properties(SurfacesTest.Volume512x512x400WorksInSlabs Assembly.RandomVolumesAreWellFormed
  Smoothing.PhantomNeverCrosses Remesh.Phantom RemeshBuildTest.BuildRemeshesThePhantomAfterSmoothing
  InterpolatedShapesTest.FinerGridsNeverIncreaseTheSphereError Remesh.SameResultForAnyThreadCount
  IncidentalOverlapsTest.IndependentlyDrawnNeighboursShareOneSurface IncidentalOverlapsTest.ThreeNeighboursMeetingAtAJunction
  InterpolationVolumeTest.FewPlaneStructuresKeepTheirSlabVolume IncidentalOverlapsTest.SplitOnTheDeviceEqualsTheHostRoundTrip
  InterpolatedShapesTest.AccuracyAtThreeGridsAgainstOff InterpolationVolumeTest.VolumesDoNotDependOnTheOtherStructures
  GridSweepTest.EveryShapeIsRightAtEveryGrid
  PROPERTIES LABELS large)
